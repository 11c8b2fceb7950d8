//! Layout of big and odd diagrams: 10 000 situations lay out in seconds
//! (with a note: the simple layered layout), the engine's work limits
//! decide what it lays out, and every output is deterministic.

use sitlog_graph::*;

/// A DM of `n` situations, each with an arc to the next and one to a
/// pseudo-random other situation (the hard case for layered layouts).
fn synthetic(n: usize) -> Diagram {
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
            functor: Some(format!("s{i}/0")),
            embedded_dm: None,
            returns: Vec::new(),
            detail: None,
            link: None,
            location: format!("main.dm:{}:1", i + 2),
        });
        if i + 1 < n {
            for (k, j) in [(0, i + 1), (1, (i * 7919) % n)] {
                g.edges.push(Edge {
                    id: format!("e:{i}.{k}"),
                    kind: EdgeKind::Arc,
                    from: format!("d0.s{i}"),
                    from_port: None,
                    to: format!("d0.s{j}"),
                    to_port: None,
                    label: format!("e{k} : empty"),
                    expectation: None,
                    location: format!("main.dm:{}:5", i + 2),
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

#[test]
fn ten_thousand_situations_in_seconds() {
    let d = synthetic(10_000);
    let start = std::time::Instant::now();
    let l = layout::layout(&d);
    let s = svg::render(&d, &l, None);
    let took = start.elapsed();
    assert!(
        l.notes.iter().any(|m| m.contains("simple layered layout")),
        "{:?}",
        l.notes
    );
    assert!(s.contains(r#"id="d0.s9999""#));
    assert!(took.as_secs() < 10, "took {took:?}");
}

/// What the engine may take is counted, not timed
/// ([`layout::engine_work`]), so a DM gets the same layout on any machine,
/// however loaded: 20 situations, the engine with crossing reduction; 40,
/// too much work for that, the engine without it; 60, too much for the
/// engine, the simple layered layout; 100, past `PLAIN_LIMIT`.
#[test]
fn medium_dms_are_laid_out_by_their_work() {
    let no_crossings =
        "DM main: edge crossings are not reduced (too much work for the layout engine)";
    let cases: [(usize, &[&str]); 4] = [
        (20, &[]),
        (40, &[no_crossings]),
        (
            60,
            &[
                "DM main is large: edge crossings are not reduced",
                "DM main: too much work for the layout engine (47004736 steps, limit 20000000); drawn with the simple layered layout",
            ],
        ),
        (
            100,
            &["DM main has 100 nodes and 198 edges: too many to lay out in a few seconds; drawn with the simple layered layout"],
        ),
    ];
    for (n, notes) in cases {
        let d = synthetic(n);
        let l = layout::layout(&d);
        assert_eq!(l.notes, notes, "{n}");
        assert_eq!(l.nodes.len(), n);
        assert_eq!(l.routes.len(), d.dms[0].edges.len());
    }
    let work =
        |n: usize, optimize| layout::engine_work(&synthetic(n).dms[0], optimize, false).unwrap();
    assert!(work(20, true) <= layout::DM_WORK_LIMIT);
    assert!(work(40, true) > layout::DM_WORK_LIMIT);
    assert!(work(40, false) <= layout::DM_WORK_LIMIT);
}

#[test]
fn deterministic_bytes() {
    let d = synthetic(25);
    let a = svg::render(&d, &layout::layout(&d), None);
    let b = svg::render(&d, &layout::layout(&d), None);
    assert_eq!(a, b);
    assert_eq!(dot::render(&d), dot::render(&d));
}

#[test]
fn empty_and_odd_diagrams() {
    let empty = Diagram::default();
    let s = svg::render(&empty, &layout::layout(&empty), None);
    assert!(s.starts_with("<svg"));
    // an edge to a node that is not there is skipped, not a panic
    let mut d = synthetic(3);
    d.dms[0].edges.push(Edge {
        id: "e:dangling".into(),
        kind: EdgeKind::Arc,
        from: "d0.s0".into(),
        from_port: Some("nowhere".into()),
        to: "missing".into(),
        to_port: None,
        label: String::new(),
        expectation: None,
        location: "main.dm:1:1".into(),
    });
    let s = svg::render(&d, &layout::layout(&d), None);
    assert!(s.contains(r#"id="d0.s2""#));
    // text that needs escaping
    let mut d = synthetic(2);
    d.dms[0].nodes[0].label = "a<b&'c'\"".into();
    let s = svg::render(&d, &layout::layout(&d), None);
    assert!(s.contains("a&lt;b&amp;&#39;c&#39;&quot;"));
    assert!(dot::render(&d).contains(r#"a<b&'c'\""#));
}

#[test]
fn functor_of_trace_ids() {
    use trace::functor_of;
    assert_eq!(functor_of("is").as_deref(), Some("is/0"));
    assert_eq!(functor_of("look([S|Ss],Seen)").as_deref(), Some("look/2"));
    assert_eq!(functor_of("f('a,b',[1,2],g(x,y))").as_deref(), Some("f/3"));
    assert_eq!(functor_of("'it''s'(x)").as_deref(), Some("it''s/1"));
    assert_eq!(functor_of("X"), None);
    assert_eq!(functor_of("42"), None);
}

#[test]
fn recorded_values_against_expectations() {
    use trace::may_match;
    assert!(may_match("[day(X)]", "[day(tuesday)]"));
    assert!(!may_match("[day(X)]", "[tuesday,'not ok']"));
    assert!(may_match(
        "[get(day,Day),apply(f(X),[In_Arg])]",
        "[tuesday,'not ok']"
    ));
    assert!(may_match("finish", "finish"));
    assert!(!may_match("finish", "loop"));
    assert!(may_match("In_Arg", "tuesday"));
    assert!(may_match("[H|T]", "[a,b]"));
    assert!(!may_match("[H|T]", "[]"));
    assert!(may_match("'ok'", "ok"));
    assert!(!may_match("success(X)", "error(x)"));
    // what the reader does not follow matches
    assert!(may_match("X == 1", "whatever"));
}
