// The JavaScript side of the aaglsd wasm module (no packages, no bundler):
// an ES module for node and browsers alike. The node test
// (wasm/tests/detect.test.mjs) and the browser demo (wasm/demo/) use it.
//
//   import { Aaglsd } from './aaglsd.mjs';
//   const lsd = await Aaglsd.load({ plain: 'aaglsd_wasm.wasm', simd: 'aaglsd_wasm_simd.wasm' });
//   // the simd128 module where the engine has simd128, else the plain one;
//   // lsd.simd tells which runs. Or, one given module:
//   const lsd = await Aaglsd.instantiate(bytesOrResponse);
//   const cfg = lsd.profile('paper');            // every Config field, by name
//   cfg.min_length_px = 20;
//   const r = lsd.detect(gray, width, height, cfg);
//   // r.segments: Float32Array of x0 y0 x1 y1 (0-based pixel centres), 4 per
//   // segment; r.scores: Float32Array, 1 per segment; r.count, r.summary,
//   // r.ms (the wasm call alone)
//
// Polarity: going from (x0, y0) to (x1, y1), the brighter side lies on the
// left as the image is displayed (x right, y down). The score is the gradient
// contrast summed along the segment, an integer below 2^24: higher is likelier
// a true line. When maxSegments is short, the module keeps the highest-scoring
// segments, best first, and summary.dropped_segments counts the rest.
//
// Every call allocates its buffers in the module's memory with alloc() and
// frees them with release() before it returns; the memory grows as needed
// (a 12-megapixel image takes about 80 MB) and never shrinks.

/** The Config fields in AaglsdConfig order, with their C types. */
export const FIELDS = [
  ['magnitude_threshold', 'f32'],
  ['anchor_margin', 'u16'],
  ['align_tolerance_deg', 'f32'],
  ['dist_tolerance_px', 'f32'],
  ['skip_min', 'u8'],
  ['skip_regular', 'u8'],
  ['skip_group', 'u8'],
  ['min_length_px', 'f32'],
  ['min_groups', 'u8'],
  ['anchor_density', 'f32'],
  ['aligned_density', 'f32'],
  ['min_score', 'u32'],
  ['extend_max_px', 'u16'],
  ['reseed', 'u8'],
  ['maxima', 'u8'],
  ['bridge_px', 'u8'],
  ['merge', 'u8'],
  ['trim', 'u8'],
  ['merge_center_px', 'f32'],
  ['merge_angle_deg', 'f32'],
  ['merge_gap_px', 'f32'],
  ['candidates_per_mille', 'u16'],
  ['max_link_pixels', 'u32'],
  ['work_per_mille', 'u32'],
  ['work_budget', 'u32'],
];

/** Profile names by their code (0, 1, 2). */
export const PROFILES = ['default', 'official', 'paper'];

/** Summary fields, in AaglsdSummary order (9 u32 on wasm32). */
export const SUMMARY_FIELDS = [
  'segments', 'dropped_segments', 'dropped_candidates', 'truncated_linkings',
  'candidates', 'groups', 'merged', 'work', 'work_cut',
];

/** Bytes of one segment in the module's output: x0 y0 x1 y1 score, five f32. */
export const SEGMENT_BYTES = 20;

/** A negative result of an export, with the status's name. */
export class AaglsdError extends Error {
  constructor(status, name, detail) {
    super(`aaglsd: ${name}${detail ? ` (${detail})` : ''}`);
    this.status = status;
    this.statusName = name;
  }
}

/**
 * The smallest module using simd128: one function `(result v128)` doing
 * i32.const 0, i8x16.splat, i8x16.popcnt (the probe of wasm-feature-detect).
 * WebAssembly.validate accepts it exactly where the engine runs simd128.
 */
const SIMD_PROBE = new Uint8Array([
  0, 97, 115, 109, 1, 0, 0, 0, 1, 5, 1, 96, 0, 1, 123, 3, 2, 1, 0, 10, 10, 1, 8, 0, 65, 0, 253, 15,
  253, 98, 11,
]);

/** A source of bytes: bytes, a Response, a URL (fetched), or a function giving one (or a promise of one). */
async function resolveSource(source) {
  let s = typeof source === 'function' ? await source() : await source;
  if (typeof s === 'string' || (typeof URL !== 'undefined' && s instanceof URL)) {
    const res = await fetch(s);
    if (!res.ok) throw new Error(`${s}: HTTP ${res.status}`);
    s = res;
  }
  return s;
}

export class Aaglsd {
  /** True when this engine runs WebAssembly simd128 (it validates a tiny simd128 module). */
  static simdSupported() {
    try {
      return WebAssembly.validate(SIMD_PROBE);
    } catch {
      return false;
    }
  }

  /**
   * Instantiates the simd128 module when the engine has simd128
   * (Aaglsd.simdSupported()), else the plain one; `lsd.simd` tells which
   * runs. Each of `plain` and `simd` is the module's bytes, a Response, a URL
   * (fetched), or a function returning one of those or a promise of one: only
   * the chosen module is fetched. `{ simd: false }` forces the plain module.
   * Both modules give bit-identical results.
   */
  static async load({ plain, simd }, { simd: useSimd = Aaglsd.simdSupported() } = {}) {
    const chosen = useSimd && simd !== undefined ? simd : plain;
    if (chosen === undefined) throw new TypeError('Aaglsd.load: no plain module given');
    return Aaglsd.instantiate(await resolveSource(chosen));
  }

  /**
   * Instantiates the module from its bytes or a fetch() Response (read
   * whole: static servers need not send the application/wasm type that
   * streaming compilation requires).
   */
  static async instantiate(source) {
    const isResponse = typeof Response !== 'undefined' && source instanceof Response;
    const bytes = isResponse ? await source.arrayBuffer() : source;
    const { instance } = await WebAssembly.instantiate(bytes, {});
    return new Aaglsd(instance.exports);
  }

  constructor(exports) {
    this.wasm = exports;
    const e = exports;
    // A module of another segment layout would be read wrongly: refuse it.
    const segmentBytes = typeof e.segment_size === 'function' ? e.segment_size() : 16;
    if (segmentBytes !== SEGMENT_BYTES) {
      throw new Error(`aaglsd: the module writes ${segmentBytes}-byte segments, this wrapper ` +
        `reads ${SEGMENT_BYTES} (x0 y0 x1 y1 score): use the wrapper of the same build`);
    }
    /** True when the module was built with simd128 (older modules: false). */
    this.simd = typeof e.simd128 === 'function' && e.simd128() === 1;
    this.configSize = e.config_size();
    this.offsets = FIELDS.map((_, i) => e.config_field_offset(i));
    // The status and field names come from the module itself.
    const names = (fn, from, to) => {
      const mark = e.alloc(64);
      const out = {};
      for (let code = from; code <= to; code++) {
        const n = fn(code, mark, 64);
        out[code] = new TextDecoder().decode(new Uint8Array(e.memory.buffer, mark, n));
      }
      e.release(mark);
      return out;
    };
    /** status code -> name, e.g. 13 -> 'out_of_bounds'. */
    this.statusNames = names(e.status_name, 0, 14);
    /** ConfigField code -> field name, e.g. 6 -> 'min_length_px'. */
    this.fieldNames = names(e.config_field_name, 1, 16);
  }

  /** Throws an AaglsdError for a negative export result; returns it otherwise. */
  check(r, detail) {
    if (r < 0) throw new AaglsdError(-r, this.statusNames[-r] ?? `status ${-r}`, detail);
    return r;
  }

  /** Runs fn with a scratch region that is freed afterwards. */
  scoped(fn) {
    const mark = this.wasm.alloc(0);
    try {
      return fn((n) => {
        const p = this.wasm.alloc(n);
        if (p === 0) throw new AaglsdError(14, 'out_of_memory', `${n} bytes`);
        return p;
      });
    } finally {
      this.wasm.release(mark);
    }
  }

  writeConfig(ptr, cfg) {
    const view = new DataView(this.wasm.memory.buffer, ptr, this.configSize);
    FIELDS.forEach(([name, type], i) => {
      const v = cfg[name];
      if (typeof v !== 'number' && typeof v !== 'boolean') {
        throw new TypeError(`config field ${name} must be a number, got ${typeof v}`);
      }
      const o = this.offsets[i];
      if (type === 'f32') view.setFloat32(o, Number(v), true);
      else if (type === 'u8') view.setUint8(o, Number(v));
      else if (type === 'u16') view.setUint16(o, Number(v), true);
      else view.setUint32(o, Number(v), true);
    });
  }

  readConfig(ptr) {
    const view = new DataView(this.wasm.memory.buffer, ptr, this.configSize);
    const cfg = {};
    FIELDS.forEach(([name, type], i) => {
      const o = this.offsets[i];
      cfg[name] = type === 'f32' ? view.getFloat32(o, true)
        : type === 'u8' ? view.getUint8(o)
          : type === 'u16' ? view.getUint16(o, true) : view.getUint32(o, true);
    });
    return cfg;
  }

  /** The configuration of a profile (name or code), as an object of every field. */
  profile(profile = 'default') {
    const code = typeof profile === 'number' ? profile : PROFILES.indexOf(profile);
    return this.scoped((alloc) => {
      const p = alloc(this.configSize);
      this.check(this.wasm.config_profile(code < 0 ? 0xffffffff : code, p), `profile ${profile}`);
      return this.readConfig(p);
    });
  }

  /** null when cfg is valid, else the name of the first field out of range. */
  validate(cfg) {
    return this.scoped((alloc) => {
      const p = alloc(this.configSize);
      this.writeConfig(p, cfg);
      const field = this.check(this.wasm.config_validate(p));
      return field === 0 ? null : this.fieldNames[field];
    });
  }

  /** Workspace bytes for a width x height image with cfg. */
  workspaceSize(width, height, cfg) {
    return this.scoped((alloc) => {
      const p = alloc(this.configSize);
      this.writeConfig(p, cfg);
      return this.check(this.wasm.workspace_size(width, height, p), `${width}x${height}`);
    });
  }

  /**
   * Detects segments in an 8-bit gray image: `pixels` holds `height` rows of
   * `width` bytes, `stride` apart. Returns { count, segments (Float32Array,
   * x0 y0 x1 y1 per segment, the brighter side on the left), scores
   * (Float32Array, one per segment), summary, ms }. At most `maxSegments`
   * (default: one per 16 pixels, at least 64), the highest-scoring when more
   * are found. Throws AaglsdError naming the status.
   */
  detect(pixels, width, height, cfg = this.profile(), { stride = width, maxSegments } = {}) {
    const e = this.wasm;
    const cap = maxSegments ?? e.default_max_segments(width, height);
    return this.scoped((alloc) => {
      const cfgPtr = alloc(this.configSize);
      this.writeConfig(cfgPtr, cfg);
      const wsLen = this.check(e.workspace_size(width, height, cfgPtr), `${width}x${height}`);
      const img = alloc(pixels.length);
      const ws = alloc(wsLen);
      const out = alloc(cap * SEGMENT_BYTES);
      const summary = alloc(SUMMARY_FIELDS.length * 4);
      // A view made after the last alloc: growing the memory detaches older ones.
      new Uint8Array(e.memory.buffer, img, pixels.length).set(pixels);
      const t0 = performance.now();
      const n = e.detect(img, pixels.length, width, height, stride, cfgPtr, ws, wsLen, out, cap,
        summary);
      const ms = performance.now() - t0;
      this.check(n, `${width}x${height}, stride ${stride}`);
      const words = new Uint32Array(e.memory.buffer, summary, SUMMARY_FIELDS.length);
      const fields = new Float32Array(e.memory.buffer, out, 5 * n);
      const segments = new Float32Array(4 * n);
      const scores = new Float32Array(n);
      for (let i = 0; i < n; i++) {
        segments.set(fields.subarray(5 * i, 5 * i + 4), 4 * i);
        scores[i] = fields[5 * i + 4];
      }
      return {
        count: n,
        segments,
        scores,
        summary: Object.fromEntries(SUMMARY_FIELDS.map((k, i) => [k, words[i]])),
        ms,
      };
    });
  }
}

/**
 * 8-bit gray from RGBA bytes (a canvas's ImageData) with OpenCV's BT.601
 * integer luma, Y = (9798 R + 19235 G + 3735 B + 16384) >> 15, the
 * conversion of the Python package's colour input: a gray picture keeps
 * its values exactly.
 */
export function rgbaToGray(rgba, width, height) {
  const gray = new Uint8Array(width * height);
  for (let i = 0, j = 0; i < gray.length; i++, j += 4) {
    gray[i] = (9798 * rgba[j] + 19235 * rgba[j + 1] + 3735 * rgba[j + 2] + 16384) >> 15;
  }
  return gray;
}
