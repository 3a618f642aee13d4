/* Shortest round-trip text of an f32 (see f32_text.h), by the free-format
 * digit generation of Steele & White as refined by Burger & Dybvig: the
 * value v = m * 2^e and its rounding interval are held as exact integer
 * ratios (r / s, with margins m- / s and m+ / s), and digits are produced
 * until the digits so far, or one more than them, fall inside the interval.
 * That is the algorithm (and the tie rule) of Rust's own fallback, so the
 * text is the same as the host's. The integers fit in 192 bits (v as large
 * as 2^128 times 20, or s as large as 2^151 times 10). */
#include "f32_text.h"

#include <string.h>

#define LIMBS 6

typedef struct {
    uint32_t w[LIMBS]; /* little-endian 32-bit limbs */
} big;

static void big_set(big *a, uint32_t v) {
    memset(a, 0, sizeof *a);
    a->w[0] = v;
}

/* a <<= n */
static void big_shl(big *a, unsigned n) {
    unsigned words = n / 32, bits = n % 32;
    for (int i = LIMBS - 1; i >= 0; i--) {
        int src = i - (int)words;
        uint32_t hi = src >= 0 ? a->w[src] : 0;
        uint32_t lo = src >= 1 ? a->w[src - 1] : 0;
        a->w[i] = bits ? (hi << bits) | (lo >> (32 - bits)) : hi;
    }
}

/* a *= k (k small) */
static void big_mul_small(big *a, uint32_t k) {
    uint64_t carry = 0;
    for (int i = 0; i < LIMBS; i++) {
        uint64_t t = (uint64_t)a->w[i] * k + carry;
        a->w[i] = (uint32_t)t;
        carry = t >> 32;
    }
}

/* c = a + b */
static void big_add(big *c, const big *a, const big *b) {
    uint64_t carry = 0;
    for (int i = 0; i < LIMBS; i++) {
        uint64_t t = (uint64_t)a->w[i] + b->w[i] + carry;
        c->w[i] = (uint32_t)t;
        carry = t >> 32;
    }
}

/* a -= b (a >= b) */
static void big_sub(big *a, const big *b) {
    uint32_t borrow = 0;
    for (int i = 0; i < LIMBS; i++) {
        uint64_t t = (uint64_t)a->w[i] - b->w[i] - borrow;
        a->w[i] = (uint32_t)t;
        borrow = (uint32_t)(t >> 63);
    }
}

static int big_cmp(const big *a, const big *b) {
    for (int i = LIMBS - 1; i >= 0; i--)
        if (a->w[i] != b->w[i]) return a->w[i] < b->w[i] ? -1 : 1;
    return 0;
}

/* The shortest digits of m * 2^e (m > 0) into `digits` (ASCII); returns
 * their count and sets *k so that the value is 0.DIGITS * 10^k. `asym`:
 * the next lower single is half as far as the next higher one (m a power
 * of two); `even`: the interval's ends read back as the value too. */
static int shortest(char digits[11], int *k, uint32_t m, int e, int asym, int even) {
    big r, s, mp, mm, t;
    /* v = r / s, the interval v - mm / s .. v + mp / s */
    big_set(&r, m);
    big_set(&s, 1);
    big_set(&mp, 1);
    big_set(&mm, 1);
    if (e >= 0) {
        big_shl(&r, (unsigned)e + 1 + (unsigned)asym);
        big_shl(&s, 1 + (unsigned)asym);
        big_shl(&mp, (unsigned)e + (unsigned)asym);
        big_shl(&mm, (unsigned)e);
    } else {
        big_shl(&r, 1 + (unsigned)asym);
        big_shl(&s, (unsigned)(1 - e) + (unsigned)asym);
        big_shl(&mp, (unsigned)asym);
    }
    /* The decimal exponent: the smallest k with v + mp / s below 10^k
     * (at most equal to it when the interval's end is excluded). */
    int n = 0;
    for (;;) {
        big_add(&t, &r, &mp);
        int c = big_cmp(&t, &s);
        if (even ? c < 0 : c <= 0) break;
        big_mul_small(&s, 10);
        n++;
    }
    for (;;) {
        big_add(&t, &r, &mp);
        big_mul_small(&t, 10);
        int c = big_cmp(&t, &s);
        if (even ? c >= 0 : c > 0) break;
        big_mul_small(&r, 10);
        big_mul_small(&mp, 10);
        big_mul_small(&mm, 10);
        n--;
    }
    *k = n;
    int len = 0;
    for (;;) {
        big_mul_small(&r, 10);
        big_mul_small(&mp, 10);
        big_mul_small(&mm, 10);
        int d = 0;
        while (big_cmp(&r, &s) >= 0) {
            big_sub(&r, &s);
            d++;
        }
        int c = big_cmp(&r, &mm);
        int low = even ? c <= 0 : c < 0; /* the digits so far are inside */
        big_add(&t, &r, &mp);
        c = big_cmp(&t, &s);
        int high = even ? c >= 0 : c > 0; /* one more than them is inside */
        if (!low && !high && len < 9) {
            digits[len++] = (char)('0' + d);
            continue;
        }
        digits[len++] = (char)('0' + d);
        if (low && high) {
            /* Both: the closer one, halfway cases upwards. */
            big_add(&t, &r, &r);
            high = big_cmp(&t, &s) >= 0;
        }
        if (high) { /* digits + 1 in the last place, carrying as Rust does */
            int i = len - 1;
            while (i >= 0 && digits[i] == '9') digits[i--] = '0';
            if (i >= 0) {
                digits[i]++;
            } else {
                digits[0] = '1';
                digits[len++] = '0';
                *k += 1;
            }
        }
        return len;
    }
}

size_t f32_text(char buf[F32_TEXT_MAX], uint32_t bits) {
    char *p = buf;
    uint32_t frac = bits & 0x7fffff;
    unsigned exp = (bits >> 23) & 0xff;
    if (exp == 0xff && frac != 0) {
        memcpy(buf, "NaN", 4);
        return 3;
    }
    if (bits >> 31) *p++ = '-';
    if (exp == 0xff) {
        memcpy(p, "inf", 4);
        return (size_t)(p - buf) + 3;
    }
    if (exp == 0 && frac == 0) {
        *p++ = '0';
        *p = 0;
        return (size_t)(p - buf);
    }
    /* Normal: m = 1.frac * 2^23, e = exp - 150; subnormal: m = frac. Rust
     * takes the interval as asymmetric for every normal power of two. */
    uint32_t m = exp ? frac | 0x800000 : frac;
    int e = exp ? (int)exp - 150 : -149;
    char digits[11];
    int k;
    /* Rust decodes a subnormal's mantissa doubled, so it always counts as
     * even (the interval's ends included). */
    int n = shortest(digits, &k, m, e, exp != 0 && frac == 0, exp == 0 || (m & 1) == 0);
    if (k <= 0) {
        *p++ = '0';
        *p++ = '.';
        for (int i = 0; i < -k; i++) *p++ = '0';
        for (int i = 0; i < n; i++) *p++ = digits[i];
    } else if (k >= n) {
        for (int i = 0; i < n; i++) *p++ = digits[i];
        for (int i = n; i < k; i++) *p++ = '0';
    } else {
        for (int i = 0; i < k; i++) *p++ = digits[i];
        *p++ = '.';
        for (int i = k; i < n; i++) *p++ = digits[i];
    }
    *p = 0;
    return (size_t)(p - buf);
}
