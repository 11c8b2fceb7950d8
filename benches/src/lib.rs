//! Generators of benchmark inputs shared by the criterion benches.

use std::fmt::Write;

/// About `lines` lines of well-formed DMs (one DM of ~40 lines per 40
/// lines), exercising situations with arguments, recursion, variables,
/// conditionals and the pipe, as one program.
pub fn dm_program(lines: usize) -> String {
    let mut out = String::with_capacity(lines * 48);
    let per_dm = one_dm(0, 0).lines().count();
    let dms = lines.div_ceil(per_dm).max(1);
    for i in 0..dms {
        out.push_str(&one_dm(i, (i + 1) % dms));
    }
    out
}

fn one_dm(i: usize, next: usize) -> String {
    let mut out = String::new();
    {
        writeln!(
            out,
            "% generated DM {i}
diag_mod(dm{i}(Arg, Status),
  [
    [ id ==> is,
      type ==> neutral,
      in_arg ==> In,
      prog ==> [inc(visits, _)],
      arcs ==> [
        empty : [say('starting'), set(last, In)] => ask(1)
      ]
    ],
    [ id ==> ask(N),
      type ==> speech,
      out_arg ==> reply(N),
      arcs ==> [
        yes : [say(ok), inc(count, C)] => (C > 3 -> call ; otherwise -> ask(2)),
        no : [say('not ok')] => ask(N),
        [item(X), colour(Y)] : [note(X, Y), set(last, X)] => call,
        stop : [] => fail
      ]
    ],
    [ id ==> call,
      type ==> recursive,
      embedded_dm ==> dm{next}(Arg, S),
      arcs ==> [
        success : [say(done), apply(when(A, B, C2), [S == ok, a, b])] => success,
        fail : [say('error')] => fail
      ]
    ],
    [ id ==> success, type ==> final, diag_mod ==> dm{i}(Arg, ok) ],
    [ id ==> fail, type ==> final, diag_mod ==> dm{i}(Arg, error) ]
  ],
  [ visits ==> 0, count ==> 0, last ==> none ]
).
"
        )
        .expect("writing to a String");
    }
    out
}

/// A DM that loops `n` times through a neutral situation, counting in a local variable.
pub fn neutral_loop(n: u64) -> String {
    format!(
        "diag_mod(main, [
  [id ==> is, type ==> neutral, arcs ==> [empty : inc(n, N) => (N >= {n} -> fs ; otherwise -> is)]],
  [id ==> fs, type ==> final]], [n ==> 0]).\n"
    )
}

/// A DM driven by scripted input: `n` `tick.` inputs, then `stop.`.
pub fn scripted_loop(n: u64) -> (String, String) {
    let dm = "diag_mod(main, [
  [id ==> is, type ==> speech, arcs ==> [tick : inc(n, _) => is, stop : [] => fs]],
  [id ==> fs, type ==> final]], [n ==> 0]).\n"
        .to_owned();
    let mut script = String::with_capacity(n as usize * 6 + 8);
    for _ in 0..n {
        script.push_str("tick.\n");
    }
    script.push_str("stop.\n");
    (dm, script)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn generated_program_checks_clean() {
        let src = dm_program(400);
        assert!(src.lines().count() >= 400);
        let (program, diags) = sitlog_compiler::load::load_sources(&[("gen.dm", &src)]);
        let (result, diags) = sitlog_compiler::check::check(program, diags);
        let errors: Vec<_> = diags.iter().filter(|d| d.is_error()).collect();
        assert!(result.is_ok(), "{errors:?}");
    }
}
