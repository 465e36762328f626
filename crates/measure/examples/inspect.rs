//! Prints how a measured file is reduced: `cargo run --example inspect -- FILE`.
fn main() {
    let path = std::env::args().nth(1).expect("file");
    let text = std::fs::read_to_string(&path).expect("read");
    let opts = propbet_measure::ReadOptions {
        name: Some(path.clone()),
        ..Default::default()
    };
    match propbet_measure::read(&text, &opts) {
        Ok(set) => {
            println!(
                "{:?} {:?} rows {} points {}",
                set.format,
                set.reduction,
                set.rows,
                set.points.len()
            );
            for n in &set.notes {
                println!("note: {n}");
            }
            println!("{}", propbet_measure::summarise_dropped(&set.dropped));
            for d in set.dropped.iter().filter(|d| d.reason.is_fault()).take(5) {
                println!("dropped {:?}", d);
            }
            for p in &set.points {
                println!(
                    "{:>22} lines {:?} rpm {:.0} sd {:?} n {} tr {} {:?} {:?}",
                    p.label,
                    p.lines,
                    p.rpm(),
                    p.omega.sd.map(propbet_units::omega_to_rpm),
                    p.omega.n,
                    p.transient,
                    p.loads,
                    p.flags
                );
            }
        }
        Err(e) => println!("error: {e}"),
    }
}
