//! Regenerates the example bodies in `assets/bodies/` from the project's own generators:
//! `cargo run --example make_assets`. A test checks that the committed files are what this
//! writes.

use std::path::Path;

fn main() -> flexmodes::Result<()> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/bodies");
    for (name, files) in flexmodes::body_file::example_bodies()? {
        flexmodes::body_file::write_files(&root.join(name), &files)?;
        println!("wrote assets/bodies/{name}/ ({} files)", files.len());
    }
    Ok(())
}
