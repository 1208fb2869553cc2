//! Point sets against CNJ's Table 2 (`noisebake report cnj`): every point method of
//! [`crate::points`] at 1000 points, the mean of 20 seeds, beside the paper's reference row.

use crate::analysis::points::{READING, table2};
use crate::points::{METHODS, Method};
use serde::Serialize;

/// Points per set.
pub const POINTS: usize = 1000;
/// Seeds averaged.
pub const SEEDS: u64 = 20;

/// One method's row (`cnj.json`).
#[derive(Clone, Debug, Serialize)]
pub struct Row {
    /// The method's name in `noisebake points`.
    pub method: &'static str,
    /// Effective Nyquist frequency ν_eff.
    pub nu_eff: f64,
    /// Anisotropy ā.
    pub anisotropy: f64,
    /// Oscillation q.
    pub q: f64,
    /// Milliseconds to make one set.
    pub ms_per_set: f64,
}

/// Measures every method.
pub fn run() -> Vec<Row> {
    METHODS
        .iter()
        .map(|&name| {
            let r = table2(Method::parse(name).expect("listed"), POINTS, SEEDS);
            Row {
                method: name,
                nu_eff: r.nu_eff,
                anisotropy: r.anisotropy,
                q: r.q,
                ms_per_set: r.ms_per_set,
            }
        })
        .collect()
}

/// The section as text: the table, the paper's row and what the columns measure.
pub fn describe(rows: &[Row]) -> Vec<String> {
    let mut out = vec![
        format!("point sets (CNJ Table 2): {POINTS} points, mean of {SEEDS} seeds"),
        format!(
            "  {:<15} {:>7} {:>8} {:>9} {:>12}",
            "method", "ν_eff", "ā", "q", "ms per set"
        ),
    ];
    for r in rows {
        out.push(format!(
            "  {:<15} {:>7.3} {:>8.2} {:>9.5} {:>12.3}",
            r.method, r.nu_eff, r.anisotropy, r.q, r.ms_per_set
        ));
    }
    out.push("  paper (CNJ, Python reference): ν_eff 0.70, ā 71.81, q 0.0097, 62.1 ms".to_string());
    out.extend(READING.lines().map(|l| format!("  {l}")));
    out
}
