//! A direct call of Triangle's `triangulate()`, which tritet 3.4.0 compiles into the binary
//! (its `c_code/triangle.c`, with `TRILIBRARY` defined), so that any switch string can be
//! sent. The declaration of `struct triangulateio` follows the field order, types and meaning
//! documented in tritet's `c_code/triangle.h` (REAL is `double`).
//!
//! The input arrays are Rust vectors that outlive the call; every output array Triangle
//! allocates is freed with its `trifree()` when the `Output` guard drops. Triangle copies the
//! input's `holelist` and `regionlist` pointers into the output: those are not freed there.

use std::ffi::{c_char, c_int, c_void, CString};

use crate::mesh::TriMesh;

// Links the crate whose build script compiles Triangle's C code into this binary.
extern crate tritet;

#[repr(C)]
struct TriangulateIo {
    pointlist: *mut f64,
    pointattributelist: *mut f64,
    pointmarkerlist: *mut c_int,
    numberofpoints: c_int,
    numberofpointattributes: c_int,

    trianglelist: *mut c_int,
    triangleattributelist: *mut f64,
    trianglearealist: *mut f64,
    neighborlist: *mut c_int,
    numberoftriangles: c_int,
    numberofcorners: c_int,
    numberoftriangleattributes: c_int,

    segmentlist: *mut c_int,
    segmentmarkerlist: *mut c_int,
    numberofsegments: c_int,

    holelist: *mut f64,
    numberofholes: c_int,

    regionlist: *mut f64,
    numberofregions: c_int,

    edgelist: *mut c_int,
    edgemarkerlist: *mut c_int,
    normlist: *mut f64,
    numberofedges: c_int,
}

impl TriangulateIo {
    /// No arrays (every pointer null, which tells Triangle to allocate an output array
    /// itself) and no counts.
    fn empty() -> TriangulateIo {
        TriangulateIo {
            pointlist: std::ptr::null_mut(),
            pointattributelist: std::ptr::null_mut(),
            pointmarkerlist: std::ptr::null_mut(),
            numberofpoints: 0,
            numberofpointattributes: 0,
            trianglelist: std::ptr::null_mut(),
            triangleattributelist: std::ptr::null_mut(),
            trianglearealist: std::ptr::null_mut(),
            neighborlist: std::ptr::null_mut(),
            numberoftriangles: 0,
            numberofcorners: 0,
            numberoftriangleattributes: 0,
            segmentlist: std::ptr::null_mut(),
            segmentmarkerlist: std::ptr::null_mut(),
            numberofsegments: 0,
            holelist: std::ptr::null_mut(),
            numberofholes: 0,
            regionlist: std::ptr::null_mut(),
            numberofregions: 0,
            edgelist: std::ptr::null_mut(),
            edgemarkerlist: std::ptr::null_mut(),
            normlist: std::ptr::null_mut(),
            numberofedges: 0,
        }
    }
}

extern "C" {
    fn triangulate(
        triswitches: *mut c_char,
        input: *mut TriangulateIo,
        output: *mut TriangulateIo,
        voronoi: *mut TriangulateIo,
    );
    fn trifree(memptr: *mut c_void);
}

/// Triangle's output, whose arrays are freed on drop.
struct Output(TriangulateIo);

impl Drop for Output {
    fn drop(&mut self) {
        let o = &self.0;
        // Not `holelist` nor `regionlist`: Triangle copies the input's pointers there.
        let arrays: [*mut c_void; 12] = [
            o.pointlist.cast(),
            o.pointattributelist.cast(),
            o.pointmarkerlist.cast(),
            o.trianglelist.cast(),
            o.triangleattributelist.cast(),
            o.trianglearealist.cast(),
            o.neighborlist.cast(),
            o.segmentlist.cast(),
            o.segmentmarkerlist.cast(),
            o.edgelist.cast(),
            o.edgemarkerlist.cast(),
            o.normlist.cast(),
        ];
        for p in arrays {
            if !p.is_null() {
                // SAFETY: every non-null output pointer but the hole and region lists (left
                // out above) was allocated by Triangle's trimalloc during `triangulate`, and
                // is freed once, here, with its matching trifree.
                unsafe { trifree(p) };
            }
        }
    }
}

/// What goes into one call: counts must fit an `int` (the caller checks).
pub struct Input<'a> {
    pub switches: &'a str,
    pub points: &'a [[f64; 2]],
    pub segments: &'a [[u32; 2]],
    pub holes: &'a [[f64; 2]],
    /// x, y, regional attribute, area bound (≤ 0: none), as Triangle's regionlist holds them.
    pub regions: &'a [[f64; 4]],
}

/// Calls `triangulate(switches, in, out, NULL)` and copies out the points and the triangles
/// (indices checked against the point count). The caller serializes calls (Triangle keeps
/// global state) and has ruled out the inputs on which Triangle exits.
pub fn run(input: &Input) -> Result<TriMesh, String> {
    let count = |n: usize, what: &str| {
        c_int::try_from(n).map_err(|_| format!("{n} {what} do not fit Triangle's int"))
    };
    let mut switches = CString::new(input.switches)
        .map_err(|_| "the switch string holds a NUL byte".to_string())?
        .into_bytes_with_nul();
    let mut points: Vec<f64> = input.points.iter().flatten().copied().collect();
    let mut segments = input
        .segments
        .iter()
        .flatten()
        .map(|&v| count(v as usize, "as a point index"))
        .collect::<Result<Vec<c_int>, String>>()?;
    let mut holes: Vec<f64> = input.holes.iter().flatten().copied().collect();
    let mut regions: Vec<f64> = input.regions.iter().flatten().copied().collect();
    let or_null = |v: &mut Vec<f64>| {
        if v.is_empty() {
            std::ptr::null_mut()
        } else {
            v.as_mut_ptr()
        }
    };
    let mut tin = TriangulateIo::empty();
    tin.pointlist = or_null(&mut points);
    tin.numberofpoints = count(input.points.len(), "points")?;
    tin.segmentlist = if segments.is_empty() {
        std::ptr::null_mut()
    } else {
        segments.as_mut_ptr()
    };
    tin.numberofsegments = count(input.segments.len(), "segments")?;
    tin.holelist = or_null(&mut holes);
    tin.numberofholes = count(input.holes.len(), "holes")?;
    tin.regionlist = or_null(&mut regions);
    tin.numberofregions = count(input.regions.len(), "regions")?;
    let mut out = Output(TriangulateIo::empty());
    // SAFETY: `switches` is NUL-terminated and `tin` points at vectors of the sizes its counts
    // give, all alive until after the call; `out` has null arrays for Triangle to allocate
    // (freed by `Output`); no `v` switch is sent, so the Voronoi output may be NULL.
    unsafe {
        triangulate(
            switches.as_mut_ptr().cast(),
            &mut tin,
            &mut out.0,
            std::ptr::null_mut(),
        )
    };
    let o = &out.0;
    let n = usize::try_from(o.numberofpoints).map_err(|_| "a negative point count")?;
    let nt = usize::try_from(o.numberoftriangles).map_err(|_| "a negative triangle count")?;
    if o.numberofcorners != 3 && nt > 0 {
        return Err(format!("{} corners per triangle", o.numberofcorners));
    }
    if (n > 0 && o.pointlist.is_null()) || (nt > 0 && o.trianglelist.is_null()) {
        return Err("no point or triangle array".into());
    }
    let coords: &[f64] = if n == 0 {
        &[]
    } else {
        // SAFETY: Triangle allocated `pointlist` with two doubles for each of its
        // `numberofpoints` points; it lives until `out` drops, after this copy.
        unsafe { std::slice::from_raw_parts(o.pointlist, 2 * n) }
    };
    let vertices: Vec<[f64; 2]> = coords.chunks_exact(2).map(|c| [c[0], c[1]]).collect();
    let corners: &[c_int] = if nt == 0 {
        &[]
    } else {
        // SAFETY: Triangle allocated `trianglelist` with `numberofcorners` (3, checked above)
        // ints for each of its `numberoftriangles` triangles; it lives until `out` drops.
        unsafe { std::slice::from_raw_parts(o.trianglelist, 3 * nt) }
    };
    let index = |v: c_int| {
        u32::try_from(v)
            .ok()
            .filter(|&i| (i as usize) < n)
            .ok_or_else(|| format!("a triangle names point {v} of {n}"))
    };
    let triangles = corners
        .chunks_exact(3)
        .map(|t| Ok([index(t[0])?, index(t[1])?, index(t[2])?]))
        .collect::<Result<Vec<_>, String>>()?;
    Ok(TriMesh {
        vertices,
        triangles,
    })
}
