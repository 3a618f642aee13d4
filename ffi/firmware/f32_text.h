/* The shortest decimal text of an IEEE 754 single that reads back as the
 * same value, written as Rust's `format!("{}", x)` writes an `f32` (the
 * host CLI's segment text): no exponent ("0.00012", "16777216"), no ".0"
 * on integers ("5"), "-0", "inf", "-inf", "NaN". Among the shortest
 * candidates the one closest to the value, halfway cases upwards. Integer
 * arithmetic only: no printf float support, no FPU needed. */
#ifndef F32_TEXT_H
#define F32_TEXT_H

#include <stddef.h>
#include <stdint.h>

/* Longest text: "-0." then 44 zeros then 9 digits, or 39 digits and a sign. */
#define F32_TEXT_MAX 64

/* Writes the text of the single with bit pattern `bits` and a NUL to `buf`
 * (F32_TEXT_MAX bytes); returns its length. */
size_t f32_text(char buf[F32_TEXT_MAX], uint32_t bits);

#endif
