//! Save/load round trips, atomic saves, and the generator at scale
//! (including that reusing class closures never changes an answer).
use crate::common;
use sitlog_kb::{gen, Kb};

#[test]
fn save_load_round_trip_of_the_paper_kbs() {
    for f in ["animals.kb", "preferences.kb", "office.kb", "updates.kb"] {
        let kb = Kb::load(&common::data(f)).unwrap();
        let text = kb.to_text();
        let again = Kb::parse(&text, f).unwrap();
        assert_eq!(again.to_text(), text, "{f}");
        // The original's own save format has no final full stop; ours neither.
        assert!(text.trim_end().ends_with(']'));
    }
}

#[test]
fn save_is_atomic_and_reloadable() {
    let dir = std::env::temp_dir().join(format!("sitlog-kb-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("kb.kb");
    let mut kb = Kb::load(&common::data("preferences.kb")).unwrap();
    kb.save(&path).unwrap();
    let upd = sitlog_syntax::read_term("add_object_property(noodles, misplaced, yes)").unwrap();
    assert_eq!(kb.update_persist(&upd, &path).unwrap(), Ok(true));
    let back = Kb::load(&path).unwrap();
    assert_eq!(back.to_text(), kb.to_text());
    assert_eq!(
        back.query("object_property_value(noodles, misplaced, X)")
            .unwrap()
            .to_line(),
        "yes"
    );
    // No temporary file is left behind.
    let names: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(names.len(), 1, "{names:?}");
    // A failed reload keeps the KB.
    let mut kb2 = back.clone();
    std::fs::write(dir.join("bad.kb"), "[class(a,none,[],[],[])]").unwrap();
    assert!(kb2.reload(&dir.join("bad.kb")).is_err());
    assert_eq!(kb2.to_text(), back.to_text());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A save keeps the file's permissions (the temporary file it goes through
/// is private), a new file is readable by others, and a failed save leaves
/// the old file and no temporary file.
#[cfg(unix)]
#[test]
fn save_keeps_permissions_and_a_failed_save_leaves_nothing() {
    use std::os::unix::fs::PermissionsExt;
    let dir = std::env::temp_dir().join(format!("sitlog-kb-perm-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let kb = Kb::load(&common::data("preferences.kb")).unwrap();
    let new = dir.join("new.kb");
    kb.save(&new).unwrap();
    let mode = |p: &std::path::Path| std::fs::metadata(p).unwrap().permissions().mode() & 0o777;
    assert_eq!(mode(&new), 0o644);
    let shared = dir.join("shared.kb");
    std::fs::write(&shared, "[]").unwrap();
    std::fs::set_permissions(&shared, std::fs::Permissions::from_mode(0o664)).unwrap();
    kb.save(&shared).unwrap();
    assert_eq!(mode(&shared), 0o664);
    // The target is a directory: the rename fails; the temporary file goes.
    let target = dir.join("a_dir.kb");
    std::fs::create_dir(&target).unwrap();
    std::fs::write(target.join("inside"), "x").unwrap();
    assert!(kb.save(&target).is_err());
    let mut names: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(names, ["a_dir.kb", "new.kb", "shared.kb"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn generated_kb_round_trips_and_shortcuts_agree() {
    let kb = gen::generate(2000, 8);
    let text = kb.to_text();
    let parsed = Kb::parse(&text, "gen").unwrap();
    assert_eq!(parsed.to_text(), text);
    let mut slow = kb.clone();
    slow.set_shortcuts(false);
    for q in [
        "property_extension(loc, X)",
        "property_extension(found_in, X)",
        "property_extension(swims, X)",
        "property_extension(stressed, X)",
        "property_extension(p3, X)",
        "relation_extension(likes, X)",
        "relation_extension(owner, X)",
        "explanation_extension(misplaced, X)",
        "explanation_extension(loc=>shelf8, X)",
        "object_property_value(o0, found_in, X)",
        "properties_of_individual(o1, X)",
        "explanation_of_individual(o2, X)",
        "explanation_of_individual(o5, X)",
        "relations_of_individual(o10, X)",
    ] {
        let fast = kb.query(q).unwrap().to_line();
        assert_eq!(fast, slow.query(q).unwrap().to_line(), "{q}");
    }
    assert_eq!(
        kb.query("class_extension(top, X)")
            .unwrap()
            .to_line()
            .matches(',')
            .count(),
        1999
    );
}

#[test]
fn a_million_individuals_property_extension() {
    // Debug builds are slow: this checks it works at scale, not its speed
    // (the criterion bench measures that in release).
    if cfg!(debug_assertions) {
        return;
    }
    let kb = gen::generate(1_000_000, 8);
    let out = kb.query("property_extension(loc, X)").unwrap().to_line();
    assert!(out.starts_with("[o0:"));
}

/// `--kb-persist` through a symbolic link (issue 31): the link stays a link
/// and its target is what changes; the lock is the target's, so a second
/// run persisting the target by its own name is refused; a path to
/// something that is not a regular file is refused before anything is read.
#[cfg(unix)]
#[test]
fn persisting_through_a_symbolic_link_writes_the_real_file() {
    use std::os::unix::fs::PermissionsExt;
    let dir = std::env::temp_dir().join(format!("sitlog-kb-link-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("real")).unwrap();
    let target = dir.join("real/k.kb");
    std::fs::write(&target, "[class(top,none,[],[],[])].\n").unwrap();
    std::fs::set_permissions(&target, std::fs::Permissions::from_mode(0o600)).unwrap();
    let link = dir.join("link.kb");
    std::os::unix::fs::symlink("real/k.kb", &link).unwrap();

    let (mut kb, lock) = Kb::open_persistent(&link).unwrap();
    assert_eq!(lock.path(), target.as_path());
    // a second run persisting the real file by its own name is excluded
    let e = sitlog_kb::lock_for_persist(&target).unwrap_err();
    assert!(e.message.contains("another process"), "{e}");
    let upd = sitlog_syntax::read_term("add_class(thing, top)").unwrap();
    assert_eq!(kb.update_persist(&upd, lock.path()).unwrap(), Ok(true));
    // saving through the link itself resolves it too
    kb.save(&link).unwrap();
    assert!(std::fs::symlink_metadata(&link)
        .unwrap()
        .file_type()
        .is_symlink());
    assert!(std::fs::read_to_string(&target).unwrap().contains("thing"));
    let mode = std::fs::metadata(&target).unwrap().permissions().mode() & 0o777;
    assert_eq!(mode, 0o600, "the target keeps its mode");
    // nothing was left beside the link
    let names: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert!(
        !names
            .iter()
            .any(|n| n.ends_with(".lock") || n.ends_with(".tmp")),
        "{names:?}"
    );
    drop(lock);

    // a link to a device is refused, naming it
    let dev = dir.join("zero.kb");
    std::os::unix::fs::symlink("/dev/zero", &dev).unwrap();
    let e = sitlog_kb::lock_for_persist(&dev).unwrap_err();
    assert!(
        e.to_string().contains("/dev/zero is not a regular file"),
        "{e}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
