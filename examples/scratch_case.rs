fn main() {
    let i: u64 = std::env::args().nth(1).unwrap().parse().unwrap();
    let s = impactcheck::perf::rigid_sample(i);
    let crit = impactcheck::perf::critical_mu(&s.b);
    println!(
        "B = {:?}\nv = {:?} mu = {} (mu/mu* - 1 = {:e}) e = {} law {:?} {:?}",
        s.b,
        s.v,
        s.mu,
        s.mu / crit - 1.0,
        s.e,
        s.law,
        s.degenerate
    );
    let r = impactcheck::models::rigid_impact::impact_with_matrix(
        &s.b,
        nalgebra::Vector3::z(),
        s.v,
        s.mu,
        s.law,
        s.e,
        1e-10,
    );
    match r {
        Ok(r) => println!(
            "{:?} {:?} {}",
            r.impulse,
            r.phases
                .iter()
                .map(|p| (p.kind.clone(), p.normal_impulse))
                .collect::<Vec<_>>(),
            r.stats
        ),
        Err(e) => println!("{e}"),
    }
    if let Ok(Some(x)) = impactcheck::models::planar_impact::impact_planar(
        &s.b,
        nalgebra::Vector3::z(),
        s.v,
        s.mu,
        s.law,
        s.e,
    ) {
        println!("exact {:?} {:?}", x.impulse, x.phases);
    }
}
