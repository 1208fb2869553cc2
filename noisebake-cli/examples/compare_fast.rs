use build_assets::fast::{self, Combine, Filter, TemporalFilter};
use noisebake_cli::analysis::filtered::{Denoiser, filtered_rmse_at};
fn ranked(v: &[f64], per: usize) -> Vec<f64> {
    let mut out = vec![0.0; v.len()];
    for (s, chunk) in v.chunks(per).enumerate() {
        let mut idx: Vec<usize> = (0..per).collect();
        idx.sort_by(|&a, &b| chunk[a].total_cmp(&chunk[b]).then(a.cmp(&b)));
        for (r, &i) in idx.iter().enumerate() {
            out[s * per + i] = (((r * 256 / per) as f64) + 0.5) / 256.0;
        }
    }
    out
}
fn main() {
    let a: Vec<usize> = std::env::args()
        .skip(1)
        .map(|a| a.parse().unwrap())
        .collect();
    let dims = [a[0], a[1], a[2]];
    let per = dims[0] * dims[1];
    let steps: Vec<f64> = (0..64).map(|i| (i as f64 + 0.5) / 64.0).collect();
    let d = Denoiser {
        spatial: Filter::Gauss { sigma: 1.3435 }.taps(),
        ema_alpha: Some(0.1),
    };
    let spec = |k: &str, extra: &str| {
        let text = format!(
            "[[texture]]\nname = \"T\"\nkind = \"{k}\"\ndims = [{}, {}, {}]\nseed = 1\n{extra}",
            dims[0], dims[1], dims[2]
        );
        build_assets::generate(
            &build_assets::spec::parse_toml(&text)
                .unwrap()
                .textures
                .remove(0),
            &mut |_, _| {},
        )
        .values()
    };
    let ign = noisebake_cli::report::compare::ign(dims);
    let rows: Vec<(&str, Vec<f64>)> = vec![
        (
            "fast b.1",
            spec(
                "fast",
                "spatial_filter = { kind = \"gauss\", sigma = 1.3435 }\ntemporal_filter = { kind = \"ema\", alpha = 0.1, beta = 0.1 }",
            ),
        ),
        (
            "fast b0",
            spec(
                "fast",
                "spatial_filter = { kind = \"gauss\", sigma = 1.3435 }\ntemporal_filter = { kind = \"ema\", alpha = 0.1, beta = 0.0 }",
            ),
        ),
        (
            "fast b0 ign",
            spec(
                "fast",
                "spatial_filter = { kind = \"gauss\", sigma = 1.3435 }\ntemporal_filter = { kind = \"ema\", alpha = 0.1, beta = 0.0 }\nstart = \"ign\"",
            ),
        ),
        (
            "fast b.1 ign",
            spec(
                "fast",
                "spatial_filter = { kind = \"gauss\", sigma = 1.3435 }\ntemporal_filter = { kind = \"ema\", alpha = 0.1, beta = 0.1 }\nstart = \"ign\"",
            ),
        ),
        ("stbn", spec("stbn", "histogram = \"slice\"")),
        ("ign ranked", ranked(&ign, per)),
        ("ign", ign),
        ("white", spec("white", "")),
    ];
    let loss = |beta: f64, v: &[f64]| {
        let mut p = noisebake_cli::report::fast::scalar_params(Combine::Product);
        p.temporal = TemporalFilter::Ema { alpha: 0.1, beta };
        let fp = p.footprint(&dims);
        fast::optimize::loss::<1, _>(dims, &fp, v, |a: &[f64; 1], b: &[f64; 1]| {
            (a[0] - b[0]).abs()
        })
    };
    for (n, v) in rows {
        let g: f64 = v.iter().map(|a| a * a - a).sum::<f64>() / v.len() as f64;
        let l0 = loss(0.0, &v);
        println!(
            "{n:10} measured {:.5}  L(b=.1) {:10.2}  L(b=0) {:10.2}  mean(a²-a)+1/6 {:+.2e}  predicted rmse(b=0) {:.5}",
            filtered_rmse_at(&v, dims, &d, &steps),
            loss(0.1, &v),
            l0,
            g + 1.0 / 6.0,
            (1.0 / 3.0 + g + l0 / (2.0 * v.len() as f64))
                .max(0.0)
                .sqrt()
        );
    }
}
