//! Prints a table of where a friction sweep's time goes on the coarse bundled brake.

#[path = "../tests/pipeline/common/mod.rs"]
mod common;

use common::best;

use squeal_brake::sweep::{SweepMethod, sweep};
use std::time::Instant;

fn main() {
    let t = Instant::now();
    let c = common::coarse();
    eprintln!("coarse brake built in {:.1?}", t.elapsed());
    let (b, r) = (&c.model.brake, &c.reference);
    let mus = common::mus(0.0, 1.0, 201);
    let cont = common::options(c);
    let dense = {
        let mut o = cont;
        o.method = SweepMethod::Dense;
        o
    };
    let (tc, sc) = best(3, || sweep(b, r, &mus, &cont).unwrap());
    println!("continuation: {:.3} s; stats {:?}", tc, sc.stats);
    println!(
        "  hopf {:?}",
        sc.hopf
            .as_ref()
            .map(|h| (h.mu0, h.frequency_hz, h.evaluations, h.bracket))
    );
    let (td, sd) = best(1, || sweep(b, r, &mus, &dense).unwrap());
    println!("dense: {:.3} s; stats {:?}", td, sd.stats);
    println!(
        "  hopf {:?}",
        sd.hopf
            .as_ref()
            .map(|h| (h.mu0, h.frequency_hz, h.evaluations, h.bracket))
    );
    let mut worst = (0.0f64, 0, 0);
    let mut swaps = 0;
    for k in 0..mus.len() {
        for br in 0..sc.branches.len() {
            let lc = sc.value(br, k);
            let ld = sd.value(br, k);
            let e = (lc - ld).norm() / ld.norm();
            if e > 1e-6 {
                swaps += 1;
            }
            if e > worst.0 && e < 1e-6 {
                worst = (e, br, k);
            }
        }
    }
    println!(
        "worst relative difference (same branch) {:?}; branch mismatches {}",
        worst, swaps
    );
    for (a, bb) in sc.crossings.iter().zip(&sd.crossings) {
        println!("  crossing cont {:?}\n           dense {:?}", a, bb);
    }
}
