//! Times the layout of synthetic DMs: `cargo run --release -p sitlog-graph --example time_layout -- N...`.
use sitlog_graph::*;

fn synthetic(n: usize, seed: u64) -> Diagram {
    let mut x = seed;
    let mut rnd = move |m: usize| {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x % m as u64) as usize
    };
    let mut g = DmGraph {
        id: "d0".into(),
        name: "main".into(),
        location: "main.dm:1:1".into(),
        nodes: Vec::new(),
        edges: Vec::new(),
    };
    for i in 0..n {
        g.nodes.push(Node {
            id: format!("d0.s{i}"),
            kind: NodeKind::Situation,
            label: format!("s{i}"),
            situation_type: Some("speech".into()),
            situation_kind: Some(SituationKind::Perceptual),
            initial: i == 0,
            functor: None,
            embedded_dm: None,
            returns: Vec::new(),
            detail: None,
            link: None,
            location: format!("main.dm:{}:1", i + 2),
        });
        if i + 1 < n {
            for (k, j) in [(0, i + 1), (1, rnd(n))] {
                g.edges.push(Edge {
                    id: format!("e:{i}.{k}"),
                    kind: EdgeKind::Arc,
                    from: format!("d0.s{i}"),
                    from_port: None,
                    to: format!("d0.s{j}"),
                    to_port: None,
                    label: format!("e{k} : empty"),
                    expectation: None,
                    location: "main.dm:1:1".into(),
                });
            }
        }
    }
    Diagram {
        title: "synthetic".into(),
        dms: vec![g],
        externals: Vec::new(),
        links: Vec::new(),
    }
}

fn main() {
    for a in std::env::args().skip(1) {
        let n: usize = a.parse().expect("a number");
        let d = synthetic(n, 88172645463325252);
        let cost = layout::engine_cost(&d.dms[0]);
        let work = layout::engine_work(&d.dms[0], cost <= layout::OPT_LIMIT, false);
        let work = work.map_or("-".to_owned(), |w| w.to_string());
        let t = std::time::Instant::now();
        let l = layout::layout(&d);
        println!(
            "{n} situations, cost {cost}, work {work}: {:.3} s {:?}",
            t.elapsed().as_secs_f64(),
            l.notes
        );
    }
}
