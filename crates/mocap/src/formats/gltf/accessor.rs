//! Reading glTF accessors, every offset, stride and count checked against the
//! buffers first: components of any type (normalized or not, as
//! `KHR_mesh_quantization` allows), interleaved views, sparse substitution.
//!
//! Inputs: the document, the buffers ([`super::document::Parsed`]), an accessor
//! and the element width expected. Output: the values as `f32` (or `u32`), one
//! flat array, `width` values per element.

use super::document::Buffer;
use crate::error::ParseError;
use gltf::accessor::{DataType, Dimensions};

/// Most elements an accessor without a buffer view (all zeros) may have.
const MAX_ZERO_ELEMENTS: usize = 1 << 22;

/// An error at `accessors[i]`.
fn error(index: usize, message: impl std::fmt::Display) -> ParseError {
    ParseError::new(0, 0, format!("accessors[{index}]: {message}"))
}

/// Components per element of a type.
fn components(d: Dimensions) -> usize {
    match d {
        Dimensions::Scalar => 1,
        Dimensions::Vec2 => 2,
        Dimensions::Vec3 => 3,
        Dimensions::Vec4 | Dimensions::Mat2 => 4,
        Dimensions::Mat3 => 9,
        Dimensions::Mat4 => 16,
    }
}

/// Bytes per component.
fn component_size(t: DataType) -> usize {
    match t {
        DataType::I8 | DataType::U8 => 1,
        DataType::I16 | DataType::U16 => 2,
        DataType::U32 | DataType::F32 => 4,
    }
}

/// One component at the start of `b` as a float (normalized when asked).
fn component(t: DataType, normalized: bool, b: &[u8]) -> f32 {
    let at = |k: usize| b.get(k).copied().unwrap_or(0);
    match (t, normalized) {
        (DataType::I8, false) => at(0) as i8 as f32,
        (DataType::I8, true) => (at(0) as i8 as f32 / 127.0).max(-1.0),
        (DataType::U8, false) => at(0) as f32,
        (DataType::U8, true) => at(0) as f32 / 255.0,
        (DataType::I16, false) => i16::from_le_bytes([at(0), at(1)]) as f32,
        (DataType::I16, true) => (i16::from_le_bytes([at(0), at(1)]) as f32 / 32767.0).max(-1.0),
        (DataType::U16, false) => u16::from_le_bytes([at(0), at(1)]) as f32,
        (DataType::U16, true) => u16::from_le_bytes([at(0), at(1)]) as f32 / 65535.0,
        (DataType::U32, _) => u32::from_le_bytes([at(0), at(1), at(2), at(3)]) as f32,
        (DataType::F32, _) => f32::from_le_bytes([at(0), at(1), at(2), at(3)]),
    }
}

/// One component at the start of `b` as an unsigned integer (indices, joints).
fn integer(t: DataType, b: &[u8]) -> Option<u32> {
    let at = |k: usize| b.get(k).copied().unwrap_or(0);
    match t {
        DataType::U8 => Some(at(0) as u32),
        DataType::U16 => Some(u16::from_le_bytes([at(0), at(1)]) as u32),
        DataType::U32 => Some(u32::from_le_bytes([at(0), at(1), at(2), at(3)])),
        _ => None,
    }
}

/// The bytes of element `k` of a strided run: `None` past the data.
fn element(data: &[u8], offset: usize, stride: usize, size: usize, k: usize) -> Option<&[u8]> {
    let start = offset.checked_add(stride.checked_mul(k)?)?;
    data.get(start..start.checked_add(size)?)
}

/// The checked byte run of a view: `(bytes of the view, stride)` for elements of
/// `size` bytes, `count` of them from `offset` (pointer `what` in messages).
fn view_run<'b>(
    view: &gltf::buffer::View<'_>,
    buffers: &'b [Buffer<'_>],
    offset: usize,
    count: usize,
    size: usize,
    what: &dyn Fn(String) -> ParseError,
) -> Result<(&'b [u8], usize), ParseError> {
    let buffer: &[u8] = buffers.get(view.buffer().index()).map_or(&[][..], |b| b);
    let end = view.offset().checked_add(view.length());
    let bytes = end.and_then(|e| buffer.get(view.offset()..e)).ok_or_else(|| {
        what(format!(
            "bufferViews[{}] (bytes {}..{}) is outside its buffer of {} bytes",
            view.index(),
            view.offset(),
            view.offset().saturating_add(view.length()),
            buffer.len()
        ))
    })?;
    let stride = view.stride().unwrap_or(size);
    if stride < size {
        return Err(what(format!(
            "bufferViews[{}].byteStride is {stride}, smaller than an element ({size} bytes)",
            view.index()
        )));
    }
    if count > 0 {
        let need = stride.checked_mul(count - 1).and_then(|n| n.checked_add(size)).and_then(|n| n.checked_add(offset));
        if need.is_none_or(|n| n > bytes.len()) {
            return Err(what(format!(
                "count {count} at byteOffset {offset} runs past the end of bufferViews[{}] ({} bytes)",
                view.index(),
                bytes.len()
            )));
        }
    }
    Ok((bytes, stride))
}

/// The accessor's values as floats, `width` per element (the accessor's own
/// component count must be `width`), sparse substitutions applied.
pub fn floats(accessor: &gltf::Accessor<'_>, buffers: &[Buffer<'_>], width: usize) -> Result<Vec<f32>, ParseError> {
    let index = accessor.index();
    let n = components(accessor.dimensions());
    if n != width {
        return Err(error(index, format!("has {n} components per element, {width} expected")));
    }
    let t = accessor.data_type();
    let size = n * component_size(t);
    let count = accessor.count();
    let what = |m: String| error(index, m);
    let mut out = match accessor.view() {
        Some(view) => {
            let (bytes, stride) = view_run(&view, buffers, accessor.offset(), count, size, &what)?;
            let packed = bytes.get(accessor.offset()..accessor.offset() + count * size);
            match packed {
                // The common case, tightly packed floats: one pass the compiler vectorises.
                Some(packed) if t == DataType::F32 && stride == size => {
                    packed.chunks_exact(4).map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]])).collect()
                }
                _ => {
                    let mut out = Vec::with_capacity(count * n);
                    for k in 0..count {
                        let e = element(bytes, accessor.offset(), stride, size, k)
                            .ok_or_else(|| what("short data".into()))?;
                        let normalized = accessor.normalized();
                        out.extend(
                            (0..n).map(|c| component(t, normalized, e.get(c * component_size(t)..).unwrap_or(&[]))),
                        );
                    }
                    out
                }
            }
        }
        None if count <= MAX_ZERO_ELEMENTS => vec![0.0; count * n],
        None => return Err(what(format!("count {count} with no bufferView: too many elements"))),
    };
    if let Some(sparse) = accessor.sparse() {
        let indices = sparse_indices(accessor, &sparse, buffers)?;
        let values = sparse.values();
        let (bytes, stride) = view_run(&values.view(), buffers, values.offset() as usize, indices.len(), size, &|m| {
            error(index, format!("sparse.values: {m}"))
        })?;
        for (k, target) in indices.into_iter().enumerate() {
            let e = element(bytes, values.offset() as usize, stride, size, k).unwrap_or(&[]);
            for c in 0..n {
                if let Some(slot) = out.get_mut(target * n + c) {
                    *slot = component(t, accessor.normalized(), e.get(c * component_size(t)..).unwrap_or(&[]));
                }
            }
        }
    }
    if let Some(k) = out.iter().position(|v| !v.is_finite()) {
        return Err(what(format!("element {} is not a finite number", k / n.max(1))));
    }
    Ok(out)
}

/// The indices of a sparse accessor, each checked against its count.
fn sparse_indices(
    accessor: &gltf::Accessor<'_>,
    sparse: &gltf::accessor::sparse::Sparse<'_>,
    buffers: &[Buffer<'_>],
) -> Result<Vec<usize>, ParseError> {
    let index = accessor.index();
    let count = sparse.count();
    if count > accessor.count() {
        return Err(error(index, format!("sparse.count {count} is more than the accessor's count")));
    }
    let ix = sparse.indices();
    let t = match ix.index_type() {
        gltf::accessor::sparse::IndexType::U8 => DataType::U8,
        gltf::accessor::sparse::IndexType::U16 => DataType::U16,
        gltf::accessor::sparse::IndexType::U32 => DataType::U32,
    };
    let size = component_size(t);
    let (bytes, _) = view_run(&ix.view(), buffers, ix.offset() as usize, count, size, &|m| {
        error(index, format!("sparse.indices: {m}"))
    })?;
    let mut out = Vec::with_capacity(count);
    for k in 0..count {
        let e = element(bytes, ix.offset() as usize, size, size, k).unwrap_or(&[]);
        let i = integer(t, e).unwrap_or(u32::MAX) as usize;
        if i >= accessor.count() {
            return Err(error(index, format!("sparse index {i} is past the accessor's count {}", accessor.count())));
        }
        out.push(i);
    }
    Ok(out)
}

/// The accessor's values as unsigned integers (scalars or vectors of `width`):
/// indices and joints, which must be of an unsigned integer type.
pub fn integers(accessor: &gltf::Accessor<'_>, buffers: &[Buffer<'_>], width: usize) -> Result<Vec<u32>, ParseError> {
    let index = accessor.index();
    let t = accessor.data_type();
    if matches!(t, DataType::F32 | DataType::I8 | DataType::I16) || accessor.normalized() {
        return Err(error(index, "holds indices, so it must be of an unsigned integer type"));
    }
    if accessor.sparse().is_some() {
        // Sparse index data is rare: read it through the float path (exact below 2^24).
        return Ok(floats(accessor, buffers, width)?.into_iter().map(|v| v as u32).collect());
    }
    let n = components(accessor.dimensions());
    if n != width {
        return Err(error(index, format!("has {n} components per element, {width} expected")));
    }
    let size = n * component_size(t);
    let count = accessor.count();
    let what = |m: String| error(index, m);
    let Some(view) = accessor.view() else {
        return if count <= MAX_ZERO_ELEMENTS { Ok(vec![0; count * n]) } else { Err(what("too many elements".into())) };
    };
    let (bytes, stride) = view_run(&view, buffers, accessor.offset(), count, size, &what)?;
    let mut out = Vec::with_capacity(count * n);
    for k in 0..count {
        let e = element(bytes, accessor.offset(), stride, size, k).ok_or_else(|| what("short data".into()))?;
        out.extend((0..n).map(|c| integer(t, e.get(c * component_size(t)..).unwrap_or(&[])).unwrap_or(0)));
    }
    Ok(out)
}
