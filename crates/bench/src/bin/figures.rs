//! Writes the figures of docs/figures/ (see `rolypoly_bench::figures`), or
//! of the folder named by its one argument, and prints the numbers of those
//! that have a table.

use std::path::PathBuf;

fn main() {
    let dir = match std::env::args_os().nth(1) {
        Some(dir) => PathBuf::from(dir),
        None => PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/figures")),
    };
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
        if let Some(table) = figure.table {
            print!("{table}");
        }
    }
}
