//! Writes the figures of docs/figures/ (see `rolypoly_bench::figures`).

use std::path::PathBuf;

fn main() {
    let dir = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/figures"));
    let figures = match rolypoly_bench::figures::all() {
        Ok(figures) => figures,
        Err(e) => {
            eprintln!("error: cannot draw the figures: {e}");
            std::process::exit(1);
        }
    };
    for figure in figures {
        let path = dir.join(figure.name);
        if let Err(e) = std::fs::write(&path, figure.svg) {
            eprintln!("error: cannot write `{}`: {e}", path.display());
            std::process::exit(1);
        }
        println!("wrote {}", path.display());
    }
}
