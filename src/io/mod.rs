//! File formats: Triangle's `.node`/`.poly`/`.ele` in and out, VTK and Gmsh out for ParaView,
//! Gmsh and meshio users, and SVG pictures (DESIGN.md "Files and command line").
mod lines;
pub mod triangle;
