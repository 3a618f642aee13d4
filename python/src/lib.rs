//! The `aaglsd._aaglsd` extension module: the Python API of the `aaglsd`
//! line segment detector (documented in `python/aaglsd/_aaglsd.pyi` and in
//! the docstrings below, which the Python tests run as doctests).
//!
//! Images come in as NumPy arrays. A 2-D `uint8` array whose rows are
//! contiguous bytes (column stride 1) at a row stride of at least the width
//! is handed to the core as it is: C-contiguous arrays, crops, row steps
//! such as `img[::2]`, padded rows. The core's `GrayImage` has no column
//! stride, so any other 2-D layout (column steps such as `img[:, ::2]`,
//! transposes, negative strides, broadcast rows) is gathered once into a
//! packed buffer, and colour images are converted to luma into one. A
//! [`Detector`] keeps that buffer, its workspace and its output across
//! frames; [`detect`] keeps them per thread for images up to
//! [`KEEP_BYTES`].
//!
//! The GIL is released for the gathering, the colour conversion and the
//! detection. Another Python thread writing to the input array during the
//! call is a data race; the docs say not to.

use std::sync::{Mutex, MutexGuard, TryLockError};
use std::time::Instant;

use aaglsd::{Config, ConfigField, Error, GrayImage, Profile, Reseed, Segment, Summary, Workspace};
use aaglsd_support::fields::{self, FIELDS, Kind, Value};
use numpy::ndarray::{ArrayView2, ArrayView3};
use numpy::{
    PyArray2, PyArrayDescrMethods, PyArrayMethods, PyReadonlyArray2, PyReadonlyArray3,
    PyUntypedArray, PyUntypedArrayMethods, dtype,
};
use pyo3::exceptions::{PyRuntimeError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt};

/// BT.601 luma in 15-bit fixed point, as OpenCV's `cvtColor` computes it
/// for 8-bit input (checked against OpenCV 4.14 and 5.0 in the tests):
/// `Y = (R*9798 + G*19235 + B*3735 + 16384) >> 15`. The weights sum to
/// 2^15, so gray pixels (R = G = B) keep their value and Y is at most 255.
fn luma(r: u8, g: u8, b: u8) -> u8 {
    let y = (u32::from(r) * 9798 + u32::from(g) * 19235 + u32::from(b) * 3735 + 16384) >> 15;
    y as u8
}

/// Channel order of 3-D input.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Order {
    Rgb,
    Bgr,
}

impl Order {
    fn parse(s: &str) -> PyResult<Self> {
        match s {
            "rgb" => Ok(Self::Rgb),
            "bgr" => Ok(Self::Bgr),
            _ => Err(PyValueError::new_err(format!(
                "color must be 'rgb' or 'bgr', got '{s}'"
            ))),
        }
    }

    fn name(self) -> &'static str {
        match self {
            Self::Rgb => "rgb",
            Self::Bgr => "bgr",
        }
    }

    /// Luma of one pixel's channels (at least 3; a 4th, alpha, is ignored).
    fn luma(self, px: &[u8]) -> u8 {
        match (self, px) {
            (Self::Rgb, [r, g, b, ..]) => luma(*r, *g, *b),
            (Self::Bgr, [b, g, r, ..]) => luma(*r, *g, *b),
            _ => 0, // not reached: 3-D input has 3 or 4 channels (checked)
        }
    }
}

// ---------------------------------------------------------------------------
// Configuration from keyword arguments

/// The Python type name of `v`, for error messages.
fn type_name(v: &Bound<'_, PyAny>) -> String {
    v.get_type()
        .name()
        .map_or_else(|_| "?".to_owned(), |n| n.to_string())
}

/// An integer argument: any `int` (or object with `__index__`) but `bool`,
/// in the range of `T`. `what` prefixes the out-of-range message.
fn int_arg<T: TryFrom<i64>>(what: &str, name: &str, v: &Bound<'_, PyAny>) -> PyResult<T> {
    let wrong = || PyTypeError::new_err(format!("{name} must be an int, got {}", type_name(v)));
    if v.is_instance_of::<PyBool>() || v.is_instance_of::<PyFloat>() {
        return Err(wrong());
    }
    let range = || PyValueError::new_err(format!("{what}{name} out of range: {v}"));
    match v.extract::<i64>() {
        Ok(i) => T::try_from(i).map_err(|_| range()),
        // An int too large for i64 (extraction raised OverflowError).
        Err(_) if v.is_instance_of::<PyInt>() => Err(range()),
        Err(_) => Err(wrong()),
    }
}

/// A config field's integer keyword.
fn int_field<T: TryFrom<i64>>(name: &str, v: &Bound<'_, PyAny>) -> PyResult<T> {
    int_arg("config field ", name, v)
}

/// Python's bool, or NumPy's (`numpy.bool_`, named `bool` in NumPy 2).
fn is_bool(v: &Bound<'_, PyAny>) -> bool {
    let tn = type_name(v);
    v.is_instance_of::<PyBool>() || tn == "bool_" || tn == "bool"
}

/// The `scores` keyword (`from_py_with`): a bool, Python's or NumPy's; any
/// other type (`None`, `1`, `"yes"`) is a `TypeError`.
fn scores_arg(v: &Bound<'_, PyAny>) -> PyResult<bool> {
    if is_bool(v) {
        v.is_truthy()
    } else {
        Err(PyTypeError::new_err(format!(
            "scores must be a bool, got {}",
            type_name(v)
        )))
    }
}

/// Sets field `name` (of type `kind`) from a Python keyword argument.
fn set_field(cfg: &mut Config, name: &str, kind: Kind, v: &Bound<'_, PyAny>) -> PyResult<()> {
    let value = match kind {
        Kind::F32 => {
            if v.is_instance_of::<PyBool>() {
                return Err(PyTypeError::new_err(format!(
                    "{name} must be a number, got bool"
                )));
            }
            let x: f64 = v.extract().map_err(|_| {
                PyTypeError::new_err(format!("{name} must be a number, got {}", type_name(v)))
            })?;
            Value::F32(x as f32) // rounds to the nearest f32, as the Rust field holds
        }
        Kind::U8 => Value::U8(int_field(name, v)?),
        Kind::U16 => Value::U16(int_field(name, v)?),
        Kind::U32 => Value::U32(int_field(name, v)?),
        Kind::Bool => {
            if !is_bool(v) {
                let tn = type_name(v);
                return Err(PyTypeError::new_err(format!(
                    "{name} must be a bool, got {tn}"
                )));
            }
            Value::Bool(v.is_truthy()?)
        }
        Kind::Reseed => {
            // "never", "once", "misfit" or "always"; a bool as never or
            // always.
            if is_bool(v) {
                Value::Reseed(if v.is_truthy()? {
                    Reseed::Always
                } else {
                    Reseed::Never
                })
            } else {
                named_value(name, kind, v, "a str or a bool")?
            }
        }
        // "strict" or "symmetric".
        Kind::Maxima => named_value(name, kind, v, "a str")?,
    };
    fields::set(cfg, name, value).map_err(PyValueError::new_err)
}

/// The value of field `name` (of type `kind`) that the str `v` names;
/// `accepted` is what the field takes, for the error when `v` is no str.
fn named_value(name: &str, kind: Kind, v: &Bound<'_, PyAny>, accepted: &str) -> PyResult<Value> {
    let text: String = v.extract().map_err(|_| {
        let tn = type_name(v);
        PyTypeError::new_err(format!("{name} must be {accepted}, got {tn}"))
    })?;
    fields::parse_value(kind, &text)
        .map_err(|what| PyValueError::new_err(format!("{name} must be {what}, got {text:?}")))
}

/// Field `name` of `cfg` as a Python object.
fn get_field<'py>(py: Python<'py>, cfg: &Config, name: &str) -> PyResult<Bound<'py, PyAny>> {
    Ok(match fields::get(cfg, name) {
        Some(Value::F32(x)) => f64::from(x).into_pyobject(py)?.into_any(),
        Some(Value::U8(x)) => x.into_pyobject(py)?.into_any(),
        Some(Value::U16(x)) => x.into_pyobject(py)?.into_any(),
        Some(Value::U32(x)) => x.into_pyobject(py)?.into_any(),
        Some(Value::Bool(x)) => x.into_pyobject(py)?.to_owned().into_any(),
        Some(Value::Reseed(r)) => fields::reseed_name(r).into_pyobject(py)?.into_any(),
        Some(Value::Maxima(m)) => fields::maxima_name(m).into_pyobject(py)?.into_any(),
        None => py.None().into_bound(py),
    })
}

/// Field `name` of `cfg` as text, for error messages.
fn show_field(cfg: &Config, name: &str) -> String {
    match fields::get(cfg, name) {
        Some(Value::F32(x)) => format!("{x:?}"),
        Some(Value::U8(x)) => x.to_string(),
        Some(Value::U16(x)) => x.to_string(),
        Some(Value::U32(x)) => x.to_string(),
        Some(Value::Bool(x)) => if x { "True" } else { "False" }.to_owned(),
        Some(Value::Reseed(r)) => format!("{:?}", fields::reseed_name(r)),
        Some(Value::Maxima(m)) => format!("{:?}", fields::maxima_name(m)),
        None => "?".to_owned(),
    }
}

/// The `ValueError` for a field that `Config::validate` rejects, naming it
/// (the three skip fields share one `ConfigField`) with its value.
fn invalid_field(cfg: &Config, field: ConfigField) -> PyErr {
    let values: Vec<String> = field
        .name()
        .split('/')
        .filter(|n| fields::kind(n).is_some())
        .map(|n| format!("{n}={}", show_field(cfg, n)))
        .collect();
    PyValueError::new_err(format!(
        "config field {} out of range: {}",
        field.name(),
        values.join(", ")
    ))
}

/// The profile's `Config` with the keyword arguments applied, validated.
fn config_from(profile: &str, fields: Option<&Bound<'_, PyDict>>) -> PyResult<Config> {
    let mut cfg = Profile::from_name(profile)
        .ok_or_else(|| {
            let names: Vec<&str> = Profile::ALL.iter().map(|p| p.name()).collect();
            PyValueError::new_err(format!(
                "unknown profile '{profile}': expected one of {}",
                names.join(", ")
            ))
        })?
        .config();
    if let Some(fields) = fields {
        for (k, v) in fields.iter() {
            let name: String = k.extract()?;
            let Some(kind) = fields::kind(&name) else {
                let names: Vec<&str> = FIELDS.iter().map(|(f, _)| *f).collect();
                return Err(PyTypeError::new_err(format!(
                    "unknown config field '{name}'; the fields are: {}",
                    names.join(", ")
                )));
            };
            set_field(&mut cfg, &name, kind, &v)?;
        }
    }
    match cfg.validate() {
        Ok(()) => Ok(cfg),
        Err(Error::InvalidConfig(field)) => Err(invalid_field(&cfg, field)),
        Err(e) => Err(core_error(e)),
    }
}

/// A core error as a Python exception (they are all bad arguments).
fn core_error(e: Error) -> PyErr {
    PyValueError::new_err(e.to_string())
}

// ---------------------------------------------------------------------------
// Images

/// The borrowed input array, 2-D gray or 3-D colour.
enum Held<'py> {
    Gray(PyReadonlyArray2<'py, u8>),
    Color(PyReadonlyArray3<'py, u8>),
}

/// How the pixels reach the core. Holds only views, so it can cross into
/// the closure that runs without the GIL.
#[derive(Clone, Copy)]
enum Source<'a> {
    /// Rows of `width` contiguous bytes, `stride` apart: passed as is.
    Direct { data: &'a [u8], stride: usize },
    /// Any other 2-D layout: gathered into a packed buffer.
    Gather(ArrayView2<'a, u8>),
    /// `(height, width, 3 or 4)` colour: converted into a packed buffer.
    Luma(ArrayView3<'a, u8>, Order),
}

#[derive(Clone, Copy)]
struct Frame<'a> {
    width: usize,
    height: usize,
    source: Source<'a>,
}

/// Borrows `image` as a `uint8` array of 2 or 3 dimensions.
fn hold<'py>(image: &Bound<'py, PyAny>) -> PyResult<Held<'py>> {
    let py = image.py();
    let arr = image.cast::<PyUntypedArray>().map_err(|_| {
        PyTypeError::new_err(format!(
            "image must be a numpy.ndarray of uint8, got {} (use numpy.asarray)",
            type_name(image)
        ))
    })?;
    let dt = arr.dtype();
    if !dt.is_equiv_to(&dtype::<u8>(py)) {
        return Err(PyTypeError::new_err(format!(
            "image must have dtype uint8, got {} (convert with .astype(numpy.uint8) after scaling to 0..255)",
            dt.str().map_or_else(|_| "?".to_owned(), |s| s.to_string())
        )));
    }
    let shape = arr.shape().to_vec();
    let borrowed = |e: numpy::BorrowError| {
        PyRuntimeError::new_err(format!("image is mutably borrowed by Rust code: {e}"))
    };
    match shape.as_slice() {
        [_, _] => Ok(Held::Gray(
            arr.cast::<PyArray2<u8>>()?
                .try_readonly()
                .map_err(borrowed)?,
        )),
        [_, _, 3 | 4] => Ok(Held::Color(
            arr.cast::<numpy::PyArray3<u8>>()?
                .try_readonly()
                .map_err(borrowed)?,
        )),
        [_, _, c] => Err(PyValueError::new_err(format!(
            "a 3-D image must have 3 (RGB or BGR) or 4 (with alpha) channels, got {c} (shape {shape:?})"
        ))),
        _ => Err(PyValueError::new_err(format!(
            "image must be 2-D (gray) or 3-D (colour), got {}-D (shape {shape:?})",
            shape.len()
        ))),
    }
}

impl Held<'_> {
    /// The image's size and how its pixels reach the core.
    fn frame(&self, order: Order) -> PyResult<Frame<'_>> {
        let (height, width, source) = match self {
            Self::Gray(a) => {
                let v = a.as_array();
                let (h, w) = v.dim();
                (h, w, direct(&v).unwrap_or(Source::Gather(v)))
            }
            Self::Color(a) => {
                let v = a.as_array();
                let (h, w, _) = v.dim();
                (h, w, Source::Luma(v, order))
            }
        };
        if width == 0 || height == 0 {
            return Err(PyValueError::new_err(format!(
                "image is empty (height {height}, width {width})"
            )));
        }
        // The core's own size checks, with its message.
        GrayImage::new(&[], width, height, width)
            .err()
            .filter(|e| matches!(e, Error::ImageTooLarge { .. }))
            .map_or(Ok(()), |e| Err(core_error(e)))?;
        Ok(Frame {
            width,
            height,
            source,
        })
    }
}

/// The zero-copy view of a 2-D array, when its layout allows one: column
/// stride 1 (or a single column) and a row stride of at least the width (or
/// a single row).
fn direct<'a>(v: &ArrayView2<'a, u8>) -> Option<Source<'a>> {
    let (h, w) = v.dim();
    let (rs, cs) = (v.strides()[0], v.strides()[1]);
    if h == 0 || w == 0 || (cs != 1 && w > 1) {
        return None;
    }
    let stride = if h == 1 {
        w
    } else {
        usize::try_from(rs).ok().filter(|&s| s >= w)?
    };
    let len = stride.checked_mul(h - 1)?.checked_add(w)?;
    // SAFETY: element (0, 0) is at `as_ptr()` and element (r, c) at
    // `r * stride + c` bytes after it (strides checked above), so the `len`
    // bytes up to the last element lie inside the array's buffer, which the
    // read-only borrow keeps alive and which Rust code does not write while
    // it is held. The core reads only the `width` bytes of each row.
    Some(Source::Direct {
        data: unsafe { std::slice::from_raw_parts(v.as_ptr(), len) },
        stride,
    })
}

/// Copies any 2-D layout into `buf` (`width * height`, rows packed).
fn gather(v: &ArrayView2<'_, u8>, buf: &mut [u8]) {
    let w = v.dim().1;
    for (dst, row) in buf.chunks_exact_mut(w).zip(v.rows()) {
        for (d, s) in dst.iter_mut().zip(row.iter()) {
            *d = *s;
        }
    }
}

/// Converts `(height, width, channels)` colour to luma in `buf`.
fn to_luma(v: &ArrayView3<'_, u8>, order: Order, buf: &mut [u8]) {
    let (_, w, c) = v.dim();
    let mut px = [0u8; 4];
    for (dst, row) in buf.chunks_exact_mut(w).zip(v.outer_iter()) {
        if let Some(packed) = row.as_slice() {
            for (d, p) in dst.iter_mut().zip(packed.chunks_exact(c)) {
                *d = order.luma(p);
            }
        } else {
            for (d, p) in dst.iter_mut().zip(row.outer_iter()) {
                for (q, s) in px.iter_mut().zip(p.iter()) {
                    *q = *s;
                }
                *d = order.luma(&px[..c.min(4)]);
            }
        }
    }
}

/// Buffers of one detection.
struct Buffers<'b> {
    workspace: &'b mut [u8],
    /// The packed copy of a gathered or colour frame (grown once).
    scratch: &'b mut Vec<u8>,
    out: &'b mut [Segment],
}

/// The buffers of detections, owned: a `Detector`'s, or those `detect`
/// keeps for its thread's next call.
#[derive(Default)]
struct Owned {
    workspace: Vec<u8>,
    scratch: Vec<u8>,
    out: Vec<Segment>,
}

impl Owned {
    /// The buffers for a call needing `workspace` bytes and `out` segments.
    /// The workspace only grows: its old bytes serve again, since each
    /// detection initialises what it reads.
    fn sized(&mut self, workspace: usize, out: usize) -> Buffers<'_> {
        if self.workspace.len() < workspace {
            self.workspace.resize(workspace, 0);
        }
        self.out.resize(out, Segment::ZERO);
        Buffers {
            workspace: &mut self.workspace,
            scratch: &mut self.scratch,
            out: &mut self.out,
        }
    }
}

/// The most `detect` keeps per thread between calls: 16 MiB, the buffers
/// of a 4-megapixel image. A loop of `detect` calls then makes no buffers
/// (making and faulting in a 640x480 image's 1.5 MB costs about 2% of its
/// detection); larger images get buffers of their own, freed after the call.
const KEEP_BYTES: usize = 16 << 20;

thread_local! {
    static KEPT: std::cell::Cell<Owned> = std::cell::Cell::default();
}

/// Runs the core on `frame` (without the GIL). Returns the summary and the
/// nanoseconds of the `aaglsd::detect` call alone.
fn run(frame: &Frame<'_>, cfg: &Config, b: Buffers<'_>) -> Result<(Summary, u64), Error> {
    let (w, h) = (frame.width, frame.height);
    let (data, stride): (&[u8], usize) = match frame.source {
        Source::Direct { data, stride } => (data, stride),
        Source::Gather(v) => {
            b.scratch.resize(w * h, 0);
            gather(&v, b.scratch);
            (b.scratch, w)
        }
        Source::Luma(v, order) => {
            b.scratch.resize(w * h, 0);
            to_luma(&v, order, b.scratch);
            (b.scratch, w)
        }
    };
    let img = GrayImage::new(data, w, h, stride)?;
    let t = Instant::now();
    let s = aaglsd::detect(&img, cfg, &mut Workspace::new(b.workspace), b.out)?;
    let ns = u64::try_from(t.elapsed().as_nanos()).unwrap_or(u64::MAX);
    Ok((s, ns))
}

/// The output capacity: `max_segments`, or one segment per 16 pixels (at
/// least 64, as the `detect` example of the Rust crate has); at most one per
/// pixel, since every segment grows from its own seed pixel.
fn capacity(
    max_segments: Option<&Bound<'_, PyAny>>,
    width: usize,
    height: usize,
) -> PyResult<usize> {
    let pixels = width.saturating_mul(height).max(1);
    let n = match max_segments {
        None => (width * height / 16).max(64),
        Some(v) => match int_arg::<usize>("", "max_segments", v)? {
            0 => return Err(PyValueError::new_err("max_segments must be at least 1")),
            n => n,
        },
    };
    Ok(n.min(pixels))
}

/// The `(N, 4)` float32 array of `segs`, or with `scores` the `(N, 5)` one
/// whose fifth column is the score: the one allocation of a call.
fn to_array<'py>(
    py: Python<'py>,
    segs: &[Segment],
    scores: bool,
) -> PyResult<Bound<'py, PyArray2<f32>>> {
    let cols = if scores { 5 } else { 4 };
    let arr = PyArray2::<f32>::zeros(py, [segs.len(), cols], false);
    {
        let mut rw = arr
            .try_readwrite()
            .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
        let flat = rw
            .as_slice_mut()
            .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
        for (dst, s) in flat.chunks_exact_mut(cols).zip(segs) {
            let row = [s.x0, s.y0, s.x1, s.y1, s.score];
            dst.copy_from_slice(row.get(..cols).unwrap_or(&row));
        }
    }
    Ok(arr)
}

/// The faster workspace size: a host has the memory for the group index
/// and the magnitude cache.
fn workspace_bytes(width: usize, height: usize, cfg: &Config) -> PyResult<usize> {
    Workspace::bytes_needed_fast(width, height, cfg)
        .ok_or_else(|| core_error(Error::ImageTooLarge { width, height }))
}

/// Detects line segments in ``image``; returns a ``(N, 4)`` float32 array of
/// ``x0 y0 x1 y1`` rows in 0-based pixel-centre coordinates (pixel
/// ``image[row, col]`` is centred at ``x = col, y = row``), or with
/// ``scores=True`` a ``(N, 5)`` one whose fifth column is each segment's
/// score: the gradient contrast summed along it, an integer below 2**24,
/// higher for likelier true lines. The brighter side of a segment lies on
/// the left of ``(x0, y0) -> (x1, y1)`` as the image is displayed (x to the
/// right, y down), so inverting the image reverses every segment.
///
/// ``image`` is a 2-D ``uint8`` array (gray), or a 3-D ``uint8`` array of
/// shape ``(height, width, 3 or 4)`` in ``color`` order (``"rgb"``, as
/// numpy and PIL give, or ``"bgr"``, as OpenCV gives; a 4th channel, alpha,
/// is ignored), converted to gray with OpenCV's BT.601 integer weights.
/// ``profile`` is ``"default"``, ``"official"`` or ``"paper"``; any
/// ``Config`` field can be set by keyword (see ``aaglsd.FIELDS``). At most
/// ``max_segments`` segments are returned (default: one per 16 pixels):
/// when the image has more, the highest-scoring ones, best first.
/// The buffers of images up to about 4 megapixels (16 MiB) are kept for
/// the calling thread's next call; a ``Detector`` keeps its own.
///
/// >>> import numpy as np, aaglsd
/// >>> img = np.full((48, 64), 200, np.uint8)
/// >>> img[12:36, 16:48] = 40  # a dark rectangle
/// >>> seg = aaglsd.detect(img)
/// >>> seg.shape, seg.dtype
/// ((4, 4), dtype('float32'))
/// >>> len(aaglsd.detect(img, min_length_px=25.0))  # only the two long sides
/// 2
/// >>> seg = aaglsd.detect(img, min_length_px=25.0, scores=True)
/// >>> seg.shape
/// (2, 5)
/// >>> seg[0].tolist()  # the bottom side, right to left: the light side below
/// [46.5, 35.5, 16.5, 35.5, 3489.0]
#[pyfunction]
#[pyo3(signature = (image, profile = "default", *, color = "rgb", max_segments = None, scores = false, **fields))]
fn detect<'py>(
    image: &Bound<'py, PyAny>,
    profile: &str,
    color: &str,
    max_segments: Option<&Bound<'_, PyAny>>,
    #[pyo3(from_py_with = scores_arg)] scores: bool,
    fields: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyArray2<f32>>> {
    let py = image.py();
    let held = hold(image)?;
    let order = Order::parse(color)?;
    let cfg = config_from(profile, fields)?;
    let frame = held.frame(order)?;
    let (w, h) = (frame.width, frame.height);
    let (need, cap) = (workspace_bytes(w, h, &cfg)?, capacity(max_segments, w, h)?);
    let keep = need + cap * size_of::<Segment>() + w * h <= KEEP_BYTES;
    let mut owned = if keep { KEPT.take() } else { Owned::default() };
    let r = py.detach(|| run(&frame, &cfg, owned.sized(need, cap)));
    let arr = r
        .map_err(core_error)
        .and_then(|(s, _)| to_array(py, owned.out.get(..s.segments).unwrap_or(&[]), scores));
    if keep {
        KEPT.set(owned);
    }
    arr
}

/// The validated configuration as a dict of every field, from a profile
/// and keyword overrides (the same arguments ``detect`` takes).
///
/// >>> import aaglsd
/// >>> cfg = aaglsd.config("paper")
/// >>> cfg["merge"], cfg["min_length_px"]
/// (True, 9.0)
/// >>> aaglsd.config(min_length_px=-1.0)
/// Traceback (most recent call last):
/// ...
/// ValueError: config field min_length_px out of range: min_length_px=-1.0
#[pyfunction]
#[pyo3(signature = (profile = "default", **fields))]
fn config<'py>(
    py: Python<'py>,
    profile: &str,
    fields: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    config_dict(py, config_from(profile, fields)?)
}

fn config_dict(py: Python<'_>, cfg: Config) -> PyResult<Bound<'_, PyDict>> {
    let d = PyDict::new(py);
    for (name, _) in &FIELDS {
        d.set_item(name, get_field(py, &cfg, name)?)?;
    }
    Ok(d)
}

/// What the last detection did (``Detector.summary``): the segments written
/// and everything dropped because a capacity was full.
#[pyclass(name = "Summary", module = "aaglsd", frozen, eq, get_all)]
#[derive(Clone, Copy, PartialEq, Eq)]
struct PySummary {
    /// Segments returned.
    segments: usize,
    /// Segments found but not returned because ``max_segments`` was reached.
    dropped_segments: usize,
    /// Group candidates dropped because the candidate list was full.
    dropped_candidates: usize,
    /// Linkings stopped early because the visited list was full.
    truncated_linkings: usize,
    /// Aligned-anchor-group candidates kept.
    candidates: usize,
    /// Aligned anchor groups extracted.
    groups: usize,
    /// Segments removed by merging (0 when merging is off).
    merged: usize,
    /// Work units spent (pixels visited, traced or compared).
    work: usize,
    /// Steps skipped because the work limit was reached.
    work_cut: usize,
}

impl From<Summary> for PySummary {
    fn from(s: Summary) -> Self {
        Self {
            segments: s.segments,
            dropped_segments: s.dropped_segments,
            dropped_candidates: s.dropped_candidates,
            truncated_linkings: s.truncated_linkings,
            candidates: s.candidates,
            groups: s.groups,
            merged: s.merged,
            work: s.work,
            work_cut: s.work_cut,
        }
    }
}

#[pymethods]
impl PySummary {
    /// True when nothing was dropped, truncated or cut by the work limit.
    #[getter]
    fn is_complete(&self) -> bool {
        self.dropped_segments == 0
            && self.dropped_candidates == 0
            && self.truncated_linkings == 0
            && self.work_cut == 0
    }

    fn __repr__(&self) -> String {
        format!(
            "Summary(segments={}, dropped_segments={}, dropped_candidates={}, \
             truncated_linkings={}, candidates={}, groups={}, merged={}, work={}, \
             work_cut={})",
            self.segments,
            self.dropped_segments,
            self.dropped_candidates,
            self.truncated_linkings,
            self.candidates,
            self.groups,
            self.merged,
            self.work,
            self.work_cut
        )
    }
}

/// What a `Detector` owns across frames.
struct State {
    bufs: Owned,
    summary: Option<PySummary>,
    last_ns: u64,
}

/// A detector for frames of one size, for video: the workspace
/// (``aaglsd`` sizes it once), the output buffer (``max_segments``, default
/// one segment per 16 pixels) and, for frames that are not zero-copy, the
/// gather buffer are kept across calls, so ``detector(frame)`` allocates
/// only the returned array. Arguments as for ``aaglsd.detect``: with
/// ``scores=True`` each call returns ``(N, 5)`` rows ``x0 y0 x1 y1 score``.
///
/// A ``Detector`` runs one frame at a time: a call made while another
/// thread's call on the same detector is running raises ``RuntimeError``
/// (give each thread its own ``Detector``).
///
/// >>> import numpy as np, aaglsd
/// >>> det = aaglsd.Detector(64, 48)
/// >>> frame = np.full((48, 64), 200, np.uint8)
/// >>> frame[12:36, 16:48] = 40
/// >>> len(det(frame)), det.summary.segments, det.summary.is_complete
/// (4, 4, True)
/// >>> det(np.zeros((48, 65), np.uint8))
/// Traceback (most recent call last):
/// ...
/// ValueError: frame is 65x48 (width x height); this Detector takes 64x48
#[pyclass(module = "aaglsd", frozen)]
struct Detector {
    width: usize,
    height: usize,
    order: Order,
    cfg: Config,
    scores: bool,
    state: Mutex<State>,
}

impl Detector {
    fn lock(&self) -> PyResult<MutexGuard<'_, State>> {
        match self.state.try_lock() {
            Ok(g) => Ok(g),
            // Nothing panics while the lock is held; were it to, the
            // buffers are still valid (each call initialises what it reads).
            Err(TryLockError::Poisoned(p)) => Ok(p.into_inner()),
            Err(TryLockError::WouldBlock) => Err(PyRuntimeError::new_err(
                "this Detector is running in another thread; give each thread its own Detector",
            )),
        }
    }
}

#[pymethods]
impl Detector {
    #[new]
    #[pyo3(signature = (width, height, profile = "default", *, color = "rgb", max_segments = None, scores = false, **fields))]
    fn new(
        width: &Bound<'_, PyAny>,
        height: &Bound<'_, PyAny>,
        profile: &str,
        color: &str,
        max_segments: Option<&Bound<'_, PyAny>>,
        #[pyo3(from_py_with = scores_arg)] scores: bool,
        fields: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        let width: usize = int_arg("", "width", width)?;
        let height: usize = int_arg("", "height", height)?;
        let order = Order::parse(color)?;
        let cfg = config_from(profile, fields)?;
        GrayImage::new(&[], width, height, width)
            .err()
            .filter(|e| !matches!(e, Error::BufferTooShort { .. }))
            .map_or(Ok(()), |e| Err(core_error(e)))?;
        let out = vec![Segment::ZERO; capacity(max_segments, width, height)?];
        Ok(Self {
            width,
            height,
            order,
            cfg,
            scores,
            state: Mutex::new(State {
                bufs: Owned {
                    workspace: vec![0u8; workspace_bytes(width, height, &cfg)?],
                    scratch: Vec::new(),
                    out,
                },
                summary: None,
                last_ns: 0,
            }),
        })
    }

    /// Detects the segments of ``frame`` (the constructor's size, any
    /// layout, gray or colour); returns them as ``aaglsd.detect`` does.
    fn __call__<'py>(&self, frame: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyArray2<f32>>> {
        let py = frame.py();
        let held = hold(frame)?;
        let f = held.frame(self.order)?;
        if (f.width, f.height) != (self.width, self.height) {
            return Err(PyValueError::new_err(format!(
                "frame is {}x{} (width x height); this Detector takes {}x{}",
                f.width, f.height, self.width, self.height
            )));
        }
        let mut guard = self.lock()?;
        let st = &mut *guard;
        let (cfg, bufs) = (self.cfg, &mut st.bufs);
        let (need, cap) = (bufs.workspace.len(), bufs.out.len());
        let (s, ns) = py
            .detach(|| run(&f, &cfg, bufs.sized(need, cap)))
            .map_err(core_error)?;
        st.summary = Some(s.into());
        st.last_ns = ns;
        to_array(
            py,
            st.bufs.out.get(..s.segments).unwrap_or(&[]),
            self.scores,
        )
    }

    /// The ``Summary`` of the last successful call, or ``None`` before one.
    #[getter]
    fn summary(&self) -> PyResult<Option<PySummary>> {
        Ok(self.lock()?.summary)
    }

    /// Nanoseconds of the Rust core's call in the last successful frame.
    #[getter]
    fn _last_detect_ns(&self) -> PyResult<u64> {
        Ok(self.lock()?.last_ns)
    }

    /// Frame width in pixels.
    #[getter]
    fn width(&self) -> usize {
        self.width
    }

    /// Frame height in pixels.
    #[getter]
    fn height(&self) -> usize {
        self.height
    }

    /// Channel order of 3-D frames, ``"rgb"`` or ``"bgr"``.
    #[getter]
    fn color(&self) -> &'static str {
        self.order.name()
    }

    /// Whether each call returns the score column (``(N, 5)`` rows).
    #[getter]
    fn scores(&self) -> bool {
        self.scores
    }

    /// Output capacity in segments.
    #[getter]
    fn max_segments(&self) -> PyResult<usize> {
        Ok(self.lock()?.bufs.out.len())
    }

    /// Bytes of the workspace (``Workspace::bytes_needed_fast``).
    #[getter]
    fn workspace_bytes(&self) -> PyResult<usize> {
        Ok(self.lock()?.bufs.workspace.len())
    }

    /// The configuration, as ``aaglsd.config`` returns it.
    #[getter]
    fn config<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        config_dict(py, self.cfg)
    }

    fn __repr__(&self) -> String {
        let scores = if self.scores { ", scores=True" } else { "" };
        format!(
            "Detector({}, {}, color={:?}{scores})",
            self.width,
            self.height,
            self.order.name()
        )
    }
}

/// How ``image`` reaches the core: ``"direct"`` (read in place),
/// ``"gather"`` (copied once into a packed buffer) or ``"luma"`` (colour,
/// converted into one). For the tests of the zero-copy layouts.
#[pyfunction]
fn _input_layout(image: &Bound<'_, PyAny>) -> PyResult<&'static str> {
    let held = hold(image)?;
    Ok(match held.frame(Order::Rgb)?.source {
        Source::Direct { .. } => "direct",
        Source::Gather(_) => "gather",
        Source::Luma(..) => "luma",
    })
}

/// The Rust core of the ``aaglsd`` package.
#[pymodule]
fn _aaglsd(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(detect, m)?)?;
    m.add_function(wrap_pyfunction!(config, m)?)?;
    m.add_function(wrap_pyfunction!(_input_layout, m)?)?;
    m.add_class::<Detector>()?;
    m.add_class::<PySummary>()?;
    let profiles: Vec<&str> = Profile::ALL.iter().map(|p| p.name()).collect();
    m.add("PROFILES", profiles)?;
    let fields: Vec<&str> = FIELDS.iter().map(|(n, _)| *n).collect();
    m.add("FIELDS", fields)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
