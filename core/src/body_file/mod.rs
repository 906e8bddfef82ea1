//! Bodies from other FE codes: the body file (TOML) naming Matrix Market stiffness and mass
//! files, node coordinates, wireframe and node sets; and the files a reduced model is
//! exported to.

mod abaqus_matrix;
mod body_location;
mod body_matrices;
mod body_spec;
mod body_writer;
mod calculix_matrix;
mod csv_table;
mod dof_map_file;
mod format_writers;
mod harwell_boeing;
mod imported_body;
mod matrix_bytes;
mod matrix_checks;
mod matrix_market;
mod nastran_dmig;
mod nastran_op4;
mod nastran_op4_ascii;
mod nastran_op4_matrix;
mod node_dof_placement;
mod npy;
mod preload;
mod spec_matrices;

pub use crate::error::BodyFileError;
pub use abaqus_matrix::parse_abaqus_matrix;
pub use body_location::BodyLocation;
pub use body_matrices::{BodyMatrices, MatrixEntries};
pub use body_spec::{
    BodySpec, DofOrder, GeometrySpec, InterfaceKind, InterfaceSpec, MatrixFiles, MatrixFormat,
    TableOrFile, Units,
};
pub use body_writer::{
    BodyFileParameters, BodyFiles, example_bodies, lower_entries, mass_lower_entries, write_body,
    write_files, write_imported_body,
};
pub use calculix_matrix::{
    calculix_equation_count, parse_calculix_dof_map, parse_calculix_dof_map_partial,
    parse_calculix_matrix,
};
pub use dof_map_file::parse_dof_map;
pub use harwell_boeing::parse_harwell_boeing;
pub use imported_body::{BodyHandle, ImportedBody, RigidSet, SYMMETRY_TOLERANCE};
pub use matrix_market::{
    MatrixMarket, MatrixMarketFormat, parse_matrix_market, read_matrix_market, write_array,
    write_coordinate_symmetric, write_coordinate_symmetric_to,
};
pub use nastran_dmig::parse_nastran_dmig;
pub use nastran_op4::parse_op4;
pub use npy::{npy_header, read_npy, write_npy};
pub use preload::{CentrifugalLoad, Preload, PreloadSpec, parse_centrifugal_load};
