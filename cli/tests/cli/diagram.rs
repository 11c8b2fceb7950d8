//! `sitlogc graph`: the papers' diagrams drawn from the IR. Snapshots of
//! the DOT, JSON and SVG of a small program with every element of the
//! notation (tests/graph/shapes), of Appendix A and of the home scenario;
//! the elements the papers name; determinism; a recorded run coloured on
//! the diagram; bad input; a 10 000-situation DM.

use crate::support::{assert_ok, sitlogc};
use sitlog_compiler::diagram::{self, Options};
use sitlog_graph::{Diagram, EdgeKind, NodeKind};
use std::path::Path;
use std::process::Command;

fn draw(app: &str, dm: Option<&str>) -> Diagram {
    let (checked, diags) =
        sitlog_cli::output::check_app(Path::new(app), Default::default()).expect("readable");
    let checked = checked.unwrap_or_else(|_| panic!("{app} has errors: {diags:?}"));
    let ir = sitlog_compiler::ir::lower(&checked);
    let options = Options {
        dm: dm.map(str::to_owned),
        main: None,
        title: sitlog_compiler::build::app_ident(Path::new(app)),
    };
    diagram::diagram(&ir, &options).expect("a diagram")
}

fn svg(d: &Diagram) -> String {
    let l = sitlog_graph::layout::layout(d);
    sitlog_graph::svg::render(d, &l, None)
}

const SHAPES: &str = "tests/graph/shapes";
const APPENDIX_A: &str = "../dms/examples/appendix_a";
const HOME: &str = "../dms/apps/home";

#[test]
fn shapes_dot_json_svg() {
    let d = draw(SHAPES, None);
    insta::assert_snapshot!("shapes_dot", sitlog_graph::dot::render(&d));
    insta::assert_snapshot!("shapes_json", d.to_json());
    insta::assert_snapshot!("shapes_svg", svg(&d));
}

#[test]
fn appendix_a_dot_json_svg() {
    let d = draw(APPENDIX_A, None);
    insta::assert_snapshot!("appendix_a_dot", sitlog_graph::dot::render(&d));
    insta::assert_snapshot!("appendix_a_json", d.to_json());
    insta::assert_snapshot!("appendix_a_svg", svg(&d));
}

#[test]
fn home_dot_json_svg() {
    let d = draw(HOME, None);
    insta::assert_snapshot!("home_dot", sitlog_graph::dot::render(&d));
    insta::assert_snapshot!("home_json", d.to_json());
    insta::assert_snapshot!("home_svg", svg(&d));
}

#[test]
fn one_dm_of_home() {
    let d = draw(HOME, Some("main"));
    assert_eq!(d.dms.len(), 1);
    // every called DM is an external box fed by a pipe
    let pipes = d.links.iter().filter(|e| e.kind == EdgeKind::Pipe).count();
    assert_eq!(pipes, 7);
    assert!(d
        .externals
        .iter()
        .any(|n| n.kind == NodeKind::ExternalDm && n.label == "learn"));
    insta::assert_snapshot!("home_main_svg", svg(&d));
}

/// Figure 3 of the 2021 paper: the elements §4.3 names.
#[test]
fn appendix_a_has_the_papers_elements() {
    let d = draw(APPENDIX_A, None);
    let main = d.dms.iter().find(|g| g.name == "main").unwrap();
    let wait = d.dms.iter().find(|g| g.name == "wait").unwrap();
    // one dotted oval per DM
    let s = svg(&d);
    assert_eq!(s.matches("<ellipse").count(), 2);
    // situations with id and type
    let label = |id: &str| {
        main.nodes
            .iter()
            .find(|n| n.id == id)
            .unwrap()
            .label
            .clone()
    };
    let sits: Vec<(String, Option<String>)> = main
        .nodes
        .iter()
        .filter(|n| n.kind == NodeKind::Situation)
        .map(|n| (n.label.clone(), n.situation_type.clone()))
        .collect();
    assert_eq!(
        sits,
        [
            ("is".to_owned(), Some("speech".to_owned())),
            ("rs".to_owned(), Some("recursive".to_owned())),
            ("fs".to_owned(), Some("final".to_owned()))
        ]
    );
    // the `h` dot with its two exits, back to `is` and on to `rs`
    let h = main
        .nodes
        .iter()
        .find(|n| n.kind == NodeKind::Function)
        .unwrap();
    assert_eq!(h.label, "h");
    let into_h: Vec<_> = main.edges.iter().filter(|e| e.to == h.id).collect();
    assert_eq!(into_h.len(), 1);
    assert_eq!(
        into_h[0].label,
        "[get(day,Day),apply(f(X),[In_Arg])] : [apply(g(X),[_])]"
    );
    let mut exits: Vec<String> = main
        .edges
        .iter()
        .filter(|e| e.from == h.id && e.kind == EdgeKind::Exit)
        .map(|e| label(&e.to))
        .collect();
    exits.sort();
    assert_eq!(exits, ["is", "rs"]);
    // `wait`'s two final situations are return dots in `rs`
    let rs = main.nodes.iter().find(|n| n.label == "rs").unwrap();
    let finals: Vec<&str> = rs.returns.iter().map(|r| r.final_id.as_str()).collect();
    assert_eq!(finals, ["fs1", "fs2"]);
    assert!(rs.returns[0].location.ends_with("wait.dm:17:7"));
    // the arcs of `rs` leave from those dots
    for (arc, dot) in [("fs1 :", &rs.returns[0].id), ("fs2 :", &rs.returns[1].id)] {
        let e = main
            .edges
            .iter()
            .find(|e| e.label.starts_with(arc))
            .unwrap();
        assert_eq!(e.from_port.as_ref(), Some(dot));
    }
    // control links from the finals to the dots, the pipe into `wait`, the out_arg
    let finals_of_wait: Vec<&str> = wait
        .nodes
        .iter()
        .filter(|n| n.situation_type.as_deref() == Some("final"))
        .map(|n| n.id.as_str())
        .collect();
    let controls: Vec<(&str, &str)> = d
        .links
        .iter()
        .filter(|e| e.kind == EdgeKind::Control)
        .map(|e| (e.from.as_str(), e.to_port.as_deref().unwrap()))
        .collect();
    assert_eq!(
        controls,
        [
            (finals_of_wait[0], rs.returns[0].id.as_str()),
            (finals_of_wait[1], rs.returns[1].id.as_str())
        ]
    );
    let pipe = d.links.iter().find(|e| e.kind == EdgeKind::Pipe).unwrap();
    assert_eq!(
        (pipe.from.as_str(), pipe.to.as_str()),
        (rs.id.as_str(), wait.nodes[0].id.as_str())
    );
    let out = d.links.iter().find(|e| e.kind == EdgeKind::OutArg).unwrap();
    assert_eq!(out.from, main.id);
}

/// Every node and edge carries its `file:line:col` as the first line of its SVG `<title>`.
#[test]
fn every_element_has_its_source_location() {
    for app in [SHAPES, APPENDIX_A, HOME] {
        let d = draw(app, None);
        let s = svg(&d);
        let ids = d
            .nodes()
            .map(|n| (n.id.clone(), n.location.clone()))
            .chain(d.edges().map(|e| (e.id.clone(), e.location.clone())))
            .chain(d.dms.iter().map(|g| (g.id.clone(), g.location.clone())));
        for (id, loc) in ids {
            let at = s
                .find(&format!("id=\"{id}\""))
                .unwrap_or_else(|| panic!("{app}: {id} is not drawn"));
            let rest = &s[at..];
            let title = rest.find("<title>").unwrap();
            assert!(
                rest[title + 7..].starts_with(&loc),
                "{app}: {id} has no title with {loc}"
            );
            let (file, line_col) = loc.split_once(".dm:").or(loc.split_once(".pl:")).unwrap();
            assert!(!file.is_empty());
            let mut parts = line_col.split(':');
            assert!(parts.next().unwrap().parse::<u32>().unwrap() > 0);
            assert!(parts.next().unwrap().parse::<u32>().unwrap() > 0);
        }
    }
}

#[test]
fn deterministic() {
    for app in [SHAPES, APPENDIX_A, HOME] {
        let (a, b) = (draw(app, None), draw(app, None));
        assert_eq!(svg(&a), svg(&b));
        assert_eq!(a.to_json(), b.to_json());
        assert_eq!(sitlog_graph::dot::render(&a), sitlog_graph::dot::render(&b));
    }
}

/// The shapes program: a ∨ before the instances of `count`, function dots
/// for the conditional and `choose`, a dashed computed exit for `dec`'s
/// value... no: `dec` is inside `count(...)`, so a ∨ again; the variable next
/// situation `S` is computed.
#[test]
fn shapes_elements() {
    let d = draw(SHAPES, None);
    let main = d.dms.iter().find(|g| g.name == "main").unwrap();
    let kinds = |k: NodeKind| main.nodes.iter().filter(|n| n.kind == k).count();
    assert_eq!(kinds(NodeKind::Disjunction), 2);
    assert_eq!(kinds(NodeKind::Function), 2);
    assert_eq!(kinds(NodeKind::Computed), 1);
    let cond = main
        .nodes
        .iter()
        .find(|n| n.kind == NodeKind::Function && n.label.contains("fast"))
        .unwrap();
    let exits: Vec<&str> = main
        .edges
        .iter()
        .filter(|e| e.from == cond.id)
        .map(|e| e.label.as_str())
        .collect();
    assert_eq!(exits, ["then", "otherwise"]);
    let choose = main.nodes.iter().find(|n| n.label == "choose").unwrap();
    let values: Vec<&str> = main
        .edges
        .iter()
        .filter(|e| e.from == choose.id)
        .map(|e| e.label.as_str())
        .collect();
    assert_eq!(values, ["quick", "ask_user"]);
    let v = main
        .nodes
        .iter()
        .find(|n| n.kind == NodeKind::Disjunction)
        .unwrap();
    let conds: Vec<&str> = main
        .edges
        .iter()
        .filter(|e| e.from == v.id)
        .map(|e| e.label.as_str())
        .collect();
    assert_eq!(conds, ["count(0)", "count(N)"]);
    let computed = main
        .edges
        .iter()
        .find(|e| e.kind == EdgeKind::Computed)
        .unwrap();
    assert_eq!(computed.label, "jump(S) : say(S)");
}

const APPENDIX_A_TRACE: &str = r#"{"dm":"main","situation":"is","expectation":"[day(tuesday)]","action":"[date(monday),next_date(tuesday)]","depth":0,"next":"is"}
{"dm":"main","situation":"is","expectation":"[tuesday,'not ok']","action":"[[day(tuesday)]:[date(monday),next_date(tuesday)]]","depth":0,"next":"rs"}
{"dm":"wait","situation":"is","expectation":"loop","action":"[1]","depth":1,"next":"fs2"}
{"dm":"wait","situation":"fs2","expectation":"empty","action":"empty","depth":1,"next":null}
{"dm":"main","situation":"rs","expectation":"fs2","action":"screen('Cont. recursive sit')","depth":0,"next":"rs"}
{"dm":"wait","situation":"is","expectation":"tuesday","action":"[1]","depth":1,"next":"fs1"}
{"dm":"wait","situation":"fs1","expectation":"empty","action":"empty","depth":1,"next":null}
{"dm":"main","situation":"rs","expectation":"fs1","action":"screen('Back to initial sit')","depth":0,"next":"is"}
{"dm":"main","situation":"is","expectation":"[day(monday)]","action":"[date(tuesday),next_date(monday)]","depth":0,"next":"is"}
{"dm":"main","situation":"is","expectation":"[monday,ok]","action":"[[day(monday)]:[date(tuesday),next_date(monday)]]","depth":0,"next":"is"}
{"dm":"main","situation":"is","expectation":"finish","action":"screen('Good Bye')","depth":0,"next":"fs"}
{"dm":"main","situation":"fs","expectation":"empty","action":"empty","depth":0,"next":null}
"#;

#[test]
fn a_recorded_run_on_the_diagram() {
    let d = draw(APPENDIX_A, None);
    let o = sitlog_graph::trace::read(&d, APPENDIX_A_TRACE).unwrap();
    assert_eq!((o.transitions, o.unmatched), (12, 0));
    let id = |dm: &str, label: &str| {
        d.dms
            .iter()
            .find(|g| g.name == dm)
            .unwrap()
            .nodes
            .iter()
            .find(|n| n.label == label)
            .unwrap()
            .id
            .clone()
    };
    assert_eq!(o.node_count(&id("main", "is")), 5);
    assert_eq!(o.node_count(&id("main", "rs")), 2);
    assert_eq!(o.node_count(&id("main", "fs")), 1);
    assert_eq!(o.node_count(&id("wait", "is")), 2);
    assert_eq!(o.node_count(&id("wait", "fs1")), 1);
    // is → h → rs, rs → rs (fs2), rs → is (fs1), is → fs
    let main = &d.dms[0];
    let h = main.nodes.iter().find(|n| n.label == "h").unwrap();
    let exit_rs = main
        .edges
        .iter()
        .find(|e| e.from == h.id && e.to == id("main", "rs"))
        .unwrap();
    assert_eq!(o.edge_count(&exit_rs.id), 1);
    // the transition `[monday,ok]` went through `h` back to `is`, not round the self-loop
    let exit_is = main
        .edges
        .iter()
        .find(|e| e.from == h.id && e.to == id("main", "is"))
        .unwrap();
    assert_eq!(o.edge_count(&exit_is.id), 1);
    assert_eq!(o.node_count(&h.id), 2);
    let self_loop = main
        .edges
        .iter()
        .find(|e| e.from == id("main", "is") && e.to == id("main", "is"))
        .unwrap();
    assert_eq!(o.edge_count(&self_loop.id), 2);
    for (from, to) in [("rs", "rs"), ("rs", "is"), ("is", "fs")] {
        let e = main
            .edges
            .iter()
            .find(|e| e.from == id("main", from) && e.to == id("main", to))
            .unwrap();
        assert_eq!(o.edge_count(&e.id), 1, "{from} -> {to}");
    }
    let l = sitlog_graph::layout::layout(&d);
    let s = sitlog_graph::svg::render(&d, &l, Some(&o));
    assert!(s.contains("visited 5 time(s)"));
    assert!(s.contains("taken 1 time(s)"));
    assert!(sitlog_graph::trace::read(&d, "not json\n").is_err());
}

#[test]
fn cli_writes_each_format() {
    let dir = crate::support::temp_root().join(format!("sitlogc-graph-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (format, start) in [("svg", "<svg"), ("dot", "digraph"), ("json", "{")] {
        let file = dir.join(format!("a.{format}"));
        let out = sitlogc()
            .args(["graph", APPENDIX_A, "--format", format, "-o"])
            .arg(&file)
            .output()
            .unwrap();
        assert_ok(&out);
        assert!(std::fs::read_to_string(&file).unwrap().starts_with(start));
    }
    // one DM to stdout
    let out = sitlogc()
        .args(["graph", APPENDIX_A, "--dm", "wait", "--format", "json"])
        .output()
        .unwrap();
    assert!(out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["dms"].as_array().unwrap().len(), 1);
    // a recorded run
    let trace = dir.join("a.jsonl");
    std::fs::write(&trace, APPENDIX_A_TRACE).unwrap();
    let out = sitlogc()
        .args(["graph", APPENDIX_A, "--trace"])
        .arg(&trace)
        .output()
        .unwrap();
    assert!(out.status.success());
    assert!(String::from_utf8_lossy(&out.stdout).contains("visited 5 time(s)"));
}

#[test]
fn cli_bad_input_gives_diagnostics_not_a_picture() {
    let out = sitlogc()
        .args(["graph", "../compiler/tests/ui/missing_parts.dm"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    assert!(out.stdout.is_empty());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("missing_parts.dm:"), "{err}");
    assert!(!err.contains("panicked"));
    let out = sitlogc()
        .args(["graph", APPENDIX_A, "--dm", "nope"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr)
        .contains("no DM named `nope` (the DMs are: main, wait)"));
    let out = sitlogc()
        .args(["graph", APPENDIX_A, "--trace", "/nonexistent/trace"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("cannot read trace"));
}

/// A big DM end to end (the 10 000-situation layout is in sitlog-graph's
/// tests: the checker, not the diagram, is what grows here).
#[test]
fn a_big_dm_end_to_end() {
    let n = 1_500;
    let mut src = String::from("diag_mod(main, [\n");
    for i in 0..n {
        if i == n - 1 {
            src.push_str(&format!("[id ==> s{i}, type ==> final]\n"));
        } else {
            let back = (i * 7919) % n;
            src.push_str(&format!(
                "[id ==> s{i}, type ==> speech, arcs ==> [a : empty => s{}, b : empty => s{back}]],\n",
                i + 1
            ));
        }
    }
    src.push_str("], []).\n");
    let (program, diags) = sitlog_compiler::load::load_sources(&[("big.dm", &src)]);
    let (checked, _) = sitlog_compiler::check::check(program, diags);
    let ir = sitlog_compiler::ir::lower(&checked.expect("no errors"));
    let start = std::time::Instant::now();
    let d = diagram::diagram(&ir, &Options::default()).unwrap();
    assert_eq!(d.situation_count(), n);
    let l = sitlog_graph::layout::layout(&d);
    let s = sitlog_graph::svg::render(&d, &l, None);
    let took = start.elapsed();
    assert!(
        l.notes.iter().any(|m| m.contains("simple layered layout")),
        "{:?}",
        l.notes
    );
    assert!(s.contains("id=\"d0.s1499\""));
    assert!(took.as_secs() < 10, "took {took:?}");
}

/// The DOT output is read by Graphviz (skipped where `dot` is not installed).
#[test]
fn dot_output_is_read_by_graphviz() {
    if Command::new("dot").arg("-V").output().is_err() {
        eprintln!("skipped: no Graphviz `dot`");
        return;
    }
    for app in [SHAPES, APPENDIX_A, HOME] {
        let text = sitlog_graph::dot::render(&draw(app, None));
        let mut child = Command::new("dot")
            .arg("-Tsvg")
            .stdin(std::process::Stdio::piped())
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        use std::io::Write;
        child
            .stdin
            .take()
            .unwrap()
            .write_all(text.as_bytes())
            .unwrap();
        let out = child.wait_with_output().unwrap();
        assert!(
            out.status.success(),
            "{app}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        assert!(String::from_utf8_lossy(&out.stdout).contains("<svg"));
    }
}

const RECOVERY: &str = "tests/graph/recovery";

fn overview(app: &str) -> Diagram {
    let (checked, diags) =
        sitlog_cli::output::check_app(Path::new(app), Default::default()).expect("readable");
    let checked = checked.unwrap_or_else(|_| panic!("{app} has errors: {diags:?}"));
    let ir = sitlog_compiler::ir::lower(&checked);
    let options = Options {
        dm: None,
        main: None,
        title: sitlog_compiler::build::app_ident(Path::new(app)),
    };
    diagram::overview(&ir, &options)
}

/// Points along a route (each cubic at 16 steps).
fn route_points(path: &[sitlog_graph::layout::Cmd]) -> Vec<sitlog_graph::layout::P> {
    use sitlog_graph::layout::{Cmd, P};
    let mut out = Vec::new();
    let mut at = P::new(0.0, 0.0);
    for c in path {
        match *c {
            Cmd::M(a) | Cmd::L(a) | Cmd::S(_, a) => {
                out.push(a);
                at = a;
            }
            Cmd::C(b, c, d) => {
                for k in 1..=16 {
                    let t = k as f64 / 16.0;
                    let u = 1.0 - t;
                    out.push(
                        at.scale(u * u * u)
                            .plus(b.scale(3.0 * u * u * t))
                            .plus(c.scale(3.0 * u * t * t))
                            .plus(d.scale(t * t * t)),
                    );
                }
                at = d;
            }
        }
    }
    out
}

/// Issue 30: `sitlogc graph dms/apps/home` was one 22981×13449 SVG. The
/// overview has one box per DM and an arrow per caller and callee, and
/// fits 1920 px across.
#[test]
fn overview_of_home_is_one_box_per_dm_and_fits_a_screen() {
    let o = overview(HOME);
    let whole = draw(HOME, None);
    assert_eq!(o.externals.len(), whole.dms.len());
    assert!(o.externals.iter().all(|n| n.kind == NodeKind::Dm));
    assert!(o.externals.iter().any(|n| n.label == "main" && n.initial));
    let calls = |from: &str, to: &str| {
        let id = |name: &str| {
            o.externals
                .iter()
                .find(|n| {
                    n.functor
                        .as_deref()
                        .is_some_and(|f| f.starts_with(&format!("{name}/")))
                })
                .unwrap()
                .id
                .clone()
        };
        o.links
            .iter()
            .any(|e| e.kind == EdgeKind::Call && e.from == id(from) && e.to == id(to))
    };
    assert!(calls("main", "serve"));
    assert!(calls("move", "reroute"));
    assert!(!calls("reroute", "move"));
    let l = sitlog_graph::layout::layout(&o);
    assert!(l.width <= 1920.0, "{}×{}", l.width, l.height);
    insta::assert_snapshot!("home_overview_svg", sitlog_graph::svg::render(&o, &l, None));
}

/// Labels wrap instead of being cut; the pipes of a page of one DM go to
/// boxes laid out beside their situations, and no pipe crosses a
/// situation (on a page or in the whole drawing).
#[test]
fn pages_wrap_labels_and_route_pipes_round_situations() {
    for dm in [
        Some("main"),
        Some("take"),
        Some("serve"),
        Some("choose"),
        None,
    ] {
        let d = draw(HOME, dm);
        let l = sitlog_graph::layout::layout(&d);
        let s = sitlog_graph::svg::render(&d, &l, None);
        assert!(!s.contains('…'), "{dm:?}: a label is cut");
        for e in d.links.iter().filter(|e| e.kind == EdgeKind::Pipe) {
            let r = &l.routes[&e.id];
            for q in route_points(&r.path) {
                let situations = d.dms.iter().flat_map(|g| &g.nodes);
                for n in situations.filter(|n| n.kind == NodeKind::Situation) {
                    if n.id == e.from || n.id == e.to {
                        continue;
                    }
                    let c = &l.nodes[&n.id];
                    let dist = q.minus(c.center).len();
                    assert!(
                        dist > c.w / 2.0 - 1.0,
                        "{dm:?}: {} crosses {}",
                        e.id,
                        n.label
                    );
                }
            }
        }
    }
    // the longest arc label of `take` is there whole, over several lines
    let d = draw(HOME, Some("take"));
    let l = sitlog_graph::layout::layout(&d);
    let long = d.dms[0].edges.iter().max_by_key(|e| e.label.len()).unwrap();
    let lines = &l.routes[&long.id].label_lines;
    assert!(lines.len() > 2, "{lines:?}");
    let joined: String = lines.concat();
    let squeeze = |s: &str| s.chars().filter(|c| !c.is_whitespace()).collect::<String>();
    assert_eq!(squeeze(&joined), squeeze(&long.label));
}

/// An arc's label (11 px text, as the SVG draws it) does not lie over a
/// situation of its DM: the layout leaves room for every line of it.
#[test]
fn arc_labels_leave_the_situations_clear() {
    let all = draw(HOME, None);
    let mut over = Vec::new();
    for name in all
        .dms
        .iter()
        .map(|g| g.name.split('(').next().unwrap().to_owned())
    {
        let d = draw(HOME, Some(&name));
        let l = sitlog_graph::layout::layout(&d);
        for g in &d.dms {
            for e in &g.edges {
                let Some(r) = l.routes.get(&e.id) else {
                    continue;
                };
                let Some(at) = r.label_at else { continue };
                let chars = r
                    .label_lines
                    .iter()
                    .map(|x| x.chars().count())
                    .max()
                    .unwrap_or(0);
                let (hw, hh) = (
                    chars as f64 * 11.0 * 0.61 / 2.0,
                    r.label_lines.len() as f64 * 13.0 / 2.0,
                );
                for n in g.nodes.iter().filter(|n| n.kind == NodeKind::Situation) {
                    let c = &l.nodes[&n.id];
                    let radius = c.w / 2.0;
                    // the point of the label's box nearest the centre
                    let qx = c.center.x.clamp(at.x - hw, at.x + hw);
                    let qy = c.center.y.clamp(at.y - hh, at.y + hh);
                    let dist = ((qx - c.center.x).powi(2) + (qy - c.center.y).powi(2)).sqrt();
                    if dist < radius - 2.0 {
                        over.push(format!("{name}: {:?} over {}", r.label_lines, n.label));
                    }
                }
            }
        }
    }
    assert!(
        over.is_empty(),
        "{} label(s) over situations:\n{}",
        over.len(),
        over.join("\n")
    );
}

/// A recovery DM is linked to the situations of the type it serves (it
/// was an isolated oval): in the whole drawing, on a page and in the overview.
#[test]
fn recovery_dms_are_linked_to_the_situations_they_serve() {
    let d = draw(RECOVERY, None);
    let pardon = d.dms.iter().find(|g| g.name == "pardon").unwrap();
    let main = d.dms.iter().find(|g| g.name == "main").unwrap();
    let rec: Vec<(&str, &str)> = d
        .links
        .iter()
        .filter(|e| e.kind == EdgeKind::Recovery)
        .map(|e| (e.from.as_str(), e.to.as_str()))
        .collect();
    let speech: Vec<&str> = main
        .nodes
        .iter()
        .filter(|n| n.situation_type.as_deref() == Some("speech"))
        .map(|n| n.id.as_str())
        .collect();
    assert_eq!(
        rec,
        speech
            .iter()
            .map(|&s| (s, pardon.nodes[0].id.as_str()))
            .collect::<Vec<_>>()
    );
    insta::assert_snapshot!("recovery_json", d.to_json());
    let page = draw(RECOVERY, Some("main"));
    assert!(page
        .links
        .iter()
        .any(|e| e.kind == EdgeKind::Recovery && e.label == "recovery (speech)"));
    assert!(page.externals.iter().any(|n| n.label == "pardon"));
    let o = overview(RECOVERY);
    assert_eq!(
        o.links
            .iter()
            .filter(|e| e.kind == EdgeKind::Recovery)
            .map(|e| (e.from.as_str(), e.to.as_str()))
            .collect::<Vec<_>>(),
        [("d0", "d1")]
    );
}

/// The command line: a program too large for one picture gives its
/// overview (with a note; `--all` the whole); `--overview`; `--out-dir`
/// writes the overview and a page per DM, linked to each other.
#[test]
fn cli_overview_and_pages() {
    let dir =
        crate::support::temp_root().join(format!("sitlogc-graph-pages-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let size = |svg: &str| -> (f64, f64) {
        let first = svg.lines().next().unwrap();
        let num = |key: &str| {
            let at = first.find(key).unwrap() + key.len();
            first[at..].split('"').next().unwrap().parse().unwrap()
        };
        (num("width=\""), num("height=\""))
    };
    let out = sitlogc().args(["graph", HOME]).output().unwrap();
    assert!(out.status.success());
    let svg = String::from_utf8(out.stdout).unwrap();
    assert!(svg.contains("class=\"node dm-box\""));
    assert!(size(&svg).0 <= 1920.0);
    assert!(String::from_utf8_lossy(&out.stderr).contains("drawn as the overview"));
    let out = sitlogc().args(["graph", HOME, "--all"]).output().unwrap();
    let svg = String::from_utf8(out.stdout).unwrap();
    assert!(size(&svg).0 > 4000.0);
    // a small program is drawn whole, as before
    let out = sitlogc().args(["graph", APPENDIX_A]).output().unwrap();
    assert!(String::from_utf8(out.stdout).unwrap().contains("<ellipse"));
    assert!(out.stderr.is_empty());
    let out = sitlogc()
        .args(["graph", APPENDIX_A, "--overview", "--format", "json"])
        .output()
        .unwrap();
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["externals"].as_array().unwrap().len(), 2);
    // pages
    let out = sitlogc()
        .args(["graph", HOME, "--out-dir"])
        .arg(&dir)
        .output()
        .unwrap();
    assert_ok(&out);
    let index = std::fs::read_to_string(dir.join("index.svg")).unwrap();
    assert!(index.contains("<a href=\"take.svg\">"));
    let html = std::fs::read_to_string(dir.join("index.html")).unwrap();
    assert!(html.contains("<a href=\"main.svg\">main</a>"));
    let pages = std::fs::read_dir(&dir).unwrap().count();
    assert_eq!(pages, 24 + 2);
    let take = std::fs::read_to_string(dir.join("take.svg")).unwrap();
    assert!(take.contains("<a href=\"regrasp.svg\">"));
    for page in std::fs::read_dir(&dir).unwrap() {
        let path = page.unwrap().path();
        if path.extension().is_some_and(|e| e == "svg") {
            let text = std::fs::read_to_string(&path).unwrap();
            assert!(!text.contains('…'), "{}", path.display());
        }
    }
    // flags that do not go together
    let out = sitlogc()
        .args(["graph", HOME, "--overview", "--dm", "main"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let _ = std::fs::remove_dir_all(&dir);
}
