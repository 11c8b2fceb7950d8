//! `sitlogc kb` (the convention of shared/notes/kb.md §6) and KB services as
//! user functions in `sitlogc run --kb`.

use crate::support::{assert_ok, sitlogc};
use std::path::{Path, PathBuf};

fn office() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../kb/tests/data/office.kb")
}

fn kb(args: &[&str]) -> (i32, String, String) {
    let out = sitlogc()
        .arg("kb")
        .arg(office())
        .args(args)
        .output()
        .unwrap();
    (
        out.status.code().unwrap(),
        String::from_utf8(out.stdout).unwrap(),
        String::from_utf8(out.stderr).unwrap(),
    )
}

#[test]
fn kb_answers_as_the_convention_says() {
    assert_eq!(
        kb(&["object_property_value(tom, found_in, X)"]).1,
        "canteen\n"
    );
    assert_eq!(
        kb(&["property_extension(stressed, X)"]).1,
        "[tom:yes,ivy:no]\n"
    );
    assert_eq!(
        kb(&[
            "--do",
            "add_object_property(ivy, late, yes)",
            "explanation_of_individual(ivy, E)"
        ])
        .1,
        "[(found_in=>canteen):stressed,stressed:late]\n"
    );
    assert_eq!(
        kb(&["explanation_of_individual(bob, E)"]),
        (0, "false\n".into(), String::new())
    );
}

#[test]
fn kb_errors_name_the_position() {
    let (code, out, err) = kb(&["nosuch(X)"]);
    assert_eq!((code, out.as_str()), (1, ""));
    assert!(err.starts_with("<query>:1:1: error:"), "{err}");
    let (code, _, err) = kb(&[
        "--do",
        "add_object_property(ivy,",
        "property_extension(late, X)",
    ]);
    assert_eq!(code, 1);
    assert!(err.starts_with("<do-1>:1:"), "{err}");
}

#[test]
fn kb_services_are_user_functions() {
    let dir = crate::support::temp_root().join(format!("sitlogc-kbrun-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("main.dm"),
        "diag_mod(main, [[id ==> is, type ==> neutral, arcs ==> [empty : \
         [apply(object_property_value(P, Q), [tom, found_in]), \
          apply(add_object_property(I, Pr, V), [ivy, late, yes]), \
          apply(property_extension(S), [late])] => fs]], \
         [id ==> fs, type ==> final]], []).\n",
    )
    .unwrap();
    let out = sitlogc()
        .args(["run", "--format", "json", "--kb"])
        .arg(office())
        .arg(&dir)
        .output()
        .unwrap();
    assert_ok(&out);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(
        v["history"][0]["action"],
        "[canteen,true,[tom:yes,ivy:yes]]"
    );
}
