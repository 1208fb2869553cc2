//! A reduced demo (32×32 pixels, 64 frames, no files) and the ordering claims of the papers that
//! hold robustly: STBN's 64-frame EMA beats independent 2D blue noise and white noise in
//! stochastic transparency and dithering (STBN §5.1–5.2, Fig. 8), and blue noise's single frame
//! after a spatial filter beats white noise (Ulichney; STBN §5).

use noisebake_demo::noises::Noise;
use noisebake_demo::{Config, run};

#[test]
fn reduced_demo_reproduces_the_papers_orderings() {
    let cfg = Config {
        size: [32, 32],
        frames: 64,
        mc_frames: 16,
        out: None,
    };
    let results = run(&cfg).expect("demo runs");
    assert_eq!(results.len(), 4);
    for app in ["transparency", "dither"] {
        let r = results.iter().find(|r| r.name == app).unwrap();
        let m = |n: Noise| &r.runs.iter().find(|(m, _)| m.noise == n).unwrap().0;
        let (stbn, ind, white) = (m(Noise::Stbn), m(Noise::Independent2d), m(Noise::White));
        let last = cfg.frames - 1;
        eprintln!(
            "{app}: EMA@64 stbn {:.4} ind2d {:.4} white {:.4}; filtered@1 ind2d {:.4} stbn {:.4} white {:.4}",
            stbn.ema[last],
            ind.ema[last],
            white.ema[last],
            ind.filtered_1,
            stbn.filtered_1,
            white.filtered_1
        );
        assert!(
            stbn.ema[last] < ind.ema[last] && stbn.ema[last] < white.ema[last],
            "{app}"
        );
        assert!(
            ind.filtered_1 < white.filtered_1 && stbn.filtered_1 < white.filtered_1,
            "{app}"
        );
        // A static mask never converges: its 64-frame average is its first frame.
        let stat = m(Noise::Blue2dStatic);
        assert!((stat.mc[last] - stat.mc[0]).abs() < 1e-9);
    }
    for r in &results {
        for (m, imgs) in &r.runs {
            assert!(
                m.mc.iter().chain(&m.ema).all(|e| e.is_finite()),
                "{} {:?}",
                r.name,
                m.noise
            );
            assert!(imgs.iter().all(|i| i.len() == 32 * 32 * r.channels));
        }
    }
}
