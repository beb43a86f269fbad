//! Factorization and lowest-mode benchmark on a 3-dof-per-node trilinear
//! box (27-point stencil, 81 nonzeros per row, like a solid mesh), printing
//! a table. One backend per process so that the peak memory (VmHWM) is that
//! backend's:
//!
//! ```text
//! nice cargo bench -p squeal-eigs --bench eigs -- lanczos
//! nice cargo bench -p squeal-eigs --features arpack --bench eigs -- arpack
//! options: --dims=NX,NY,NZ (default 40,36,34: 146,880 dofs)  --nev=N (default 50)
//! ```

use squeal_eigs::model_problems::box_vector;
use squeal_eigs::{Backend, CholeskyOptions, EigOptions, SparseCholesky, lowest_modes_with_factor};
use std::time::Instant;

mod common;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let backend = if args.iter().any(|a| a == "arpack") {
        Backend::Arpack
    } else {
        Backend::Lanczos
    };
    let mut dims = [40usize, 36, 34];
    let mut nev = 50usize;
    for a in &args {
        if let Some(d) = a.strip_prefix("--dims=") {
            let v: Vec<usize> = d.split(',').filter_map(|x| x.parse().ok()).collect();
            if v.len() == 3 {
                dims = [v[0], v[1], v[2]];
            }
        }
        if let Some(x) = a.strip_prefix("--nev=").and_then(|x| x.parse().ok()) {
            nev = x;
        }
    }
    let t = Instant::now();
    let p = box_vector(dims, [0.4, 0.36, 0.34]);
    let assemble = t.elapsed();
    let n = p.k.nrows();
    println!(
        "# squeal-eigs bench: box_vector {dims:?}, n = {n}, nnz(K) = {}, nev = {nev}, backend {backend:?}",
        p.k.compute_nnz()
    );
    println!("# threads: {}", rayon::current_num_threads());
    println!("assemble (s)            {:8.2}", assemble.as_secs_f64());
    let t = Instant::now();
    let f = SparseCholesky::factorize_with(p.k.as_ref(), &CholeskyOptions::default())
        .expect("factorization");
    let total_factor = t.elapsed();
    common::print_factor(&f.stats(), total_factor);
    let t = Instant::now();
    let x = f
        .solve(faer::Mat::<f64>::ones(n, 64).as_ref())
        .expect("solve");
    println!("64-RHS solve (s)        {:8.2}", t.elapsed().as_secs_f64());
    drop(x);
    let t = Instant::now();
    for _ in 0..20 {
        let mut c = faer::Col::<f64>::ones(n);
        f.solve_col_in_place(&mut c).expect("solve");
    }
    println!(
        "1-RHS solve (ms)        {:8.2}",
        t.elapsed().as_secs_f64() * 1000.0 / 20.0
    );
    let opts = {
        let mut o = EigOptions::default();
        o.backend = backend;
        o
    };
    let t = Instant::now();
    let modes =
        lowest_modes_with_factor(p.k.as_ref(), p.m.as_ref(), &f, nev, &opts).expect("eigensolve");
    let total = t.elapsed();
    let st = modes.stats;
    println!("eigensolve total (s)    {:8.2}", total.as_secs_f64());
    println!(
        "  iteration (s)         {:8.2}",
        (st.solve_time - st.sturm_time).as_secs_f64()
    );
    println!(
        "  Sturm check (s)       {:8.2}",
        st.sturm_time.as_secs_f64()
    );
    println!(
        "  iterations / rounds   {:>5} / {}",
        st.iterations, st.rounds
    );
    println!("  OP applications       {:>8}", st.operator_applications);
    println!("  ncv                   {:>8}", st.ncv);
    println!(
        "  lowest / highest w^2  {:.6e} / {:.6e}",
        modes.values[0],
        modes.values[nev - 1]
    );
    println!(
        "  worst backward error  {:.2e}",
        modes.residuals.iter().copied().fold(0.0, f64::max)
    );
    println!("peak memory VmHWM (MiB) {:8.1}", common::peak_mib());
}
