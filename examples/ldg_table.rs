//! Prints the low-discrepancy-grid table of the plus-shaped / R2 blog post for noisebake's grids
//! and a blue-noise mask: how far stochastic-transparency coverage lands from 10/20/30/40 %, and
//! the spread of values in plus-shaped and 3×3 neighbourhoods (tests/ldg.rs asserts the same
//! numbers as bounds).
//!
//! `cargo run --release --example ldg_table`

#[path = "../tests/support/ldg_table.rs"]
mod ldg_table;

fn main() {
    ldg_table::print(&ldg_table::table());
}
