//! Command-line conventions: shell completions, the manual page, `--color`
//! and `NO_COLOR` for diagnostics.

use std::process::Command;

fn sitlogc() -> Command {
    let mut cmd = crate::support::sitlogc();
    cmd.env_remove("NO_COLOR");
    cmd
}

#[test]
fn completions_for_every_shell() {
    for (shell, marker) in [
        ("bash", "_sitlogc()"),
        ("zsh", "#compdef sitlogc"),
        ("fish", "complete -c sitlogc"),
        ("elvish", "sitlogc"),
        ("powershell", "sitlogc"),
    ] {
        let out = sitlogc().args(["completions", shell]).output().unwrap();
        assert_eq!(out.status.code(), Some(0), "{shell}");
        let text = String::from_utf8(out.stdout).unwrap();
        assert!(text.contains(marker), "{shell}: {text}");
        // Subcommands and their options are completed.
        assert!(
            text.contains("build") && text.contains("--script"),
            "{shell}"
        );
    }
    let out = sitlogc().args(["completions", "tcsh"]).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
}

#[test]
fn man_page_on_stdout_and_into_a_directory() {
    let out = sitlogc().arg("man").output().unwrap();
    assert_eq!(out.status.code(), Some(0));
    let page = String::from_utf8(out.stdout).unwrap();
    assert!(page.contains(".TH sitlogc 1"), "{page}");
    assert!(
        page.contains("sitlogc\\-build(1)") || page.contains("build"),
        "{page}"
    );
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("man1");
    let out = sitlogc()
        .arg("man")
        .arg("--dir")
        .arg(&dir)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0));
    for page in [
        "sitlogc.1",
        "sitlogc-run.1",
        "sitlogc-build.1",
        "sitlogc-new.1",
    ] {
        let text = std::fs::read_to_string(dir.join(page)).unwrap();
        assert!(text.starts_with(".ie"), "{page}");
    }
    let run = std::fs::read_to_string(dir.join("sitlogc-run.1")).unwrap();
    assert!(run.contains("script"), "{run}");
}

#[test]
fn color_flag_and_no_color() {
    let tmp = tempfile::tempdir().unwrap();
    std::fs::write(
        tmp.path().join("main.dm"),
        "diag_mod(main, [[id ==> is, type ==> final]], [] .\n",
    )
    .unwrap();
    let check = |args: &[&str], no_color: Option<&str>| {
        let mut cmd = sitlogc();
        cmd.args(args).arg(tmp.path());
        if let Some(v) = no_color {
            cmd.env("NO_COLOR", v);
        }
        let out = cmd.output().unwrap();
        assert_eq!(out.status.code(), Some(1));
        String::from_utf8(out.stderr).unwrap()
    };
    let escape = '\u{1b}';
    // stderr is a pipe here: auto means no colour.
    assert!(!check(&["check"], None).contains(escape));
    assert!(check(&["check", "--color", "always"], None).contains(escape));
    // The flag is global: before the subcommand too; explicit beats NO_COLOR.
    assert!(check(&["--color", "always", "check"], Some("1")).contains(escape));
    assert!(!check(&["check", "--color", "never"], None).contains(escape));
    // run's diagnostics too.
    assert!(check(&["run", "--color=always"], None).contains(escape));
    assert!(!check(&["run", "--color=never"], None).contains(escape));
    let out = sitlogc()
        .args(["check", "--color", "sometimes"])
        .arg(tmp.path())
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
}
