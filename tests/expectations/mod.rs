//! Tests that can write their own expectations anew (`BLESS=1`,
//! `REGENERATE_SCENES=1`): such a run compares the code with itself, so it
//! must never pass in CI, where `CI` is set.

/// Whether the variable `var` asks the test to write its expectations
/// anew; panics when it does in CI.
pub fn rewriting(var: &str) -> bool {
    match decide(
        std::env::var_os(var).is_some(),
        std::env::var("CI").ok().as_deref(),
    ) {
        Ok(on) => on,
        Err(()) => panic!(
            "{var} is set while CI is: a run that rewrites its own expectations checks \
             nothing, so it cannot pass in CI; unset {var} (and bless locally)"
        ),
    }
}

/// `Ok(rewrite)`, or `Err` when asked to rewrite in CI (`ci`: the value of `CI`).
pub fn decide(asked: bool, ci: Option<&str>) -> Result<bool, ()> {
    let in_ci = ci.is_some_and(|v| !v.is_empty() && v != "0" && !v.eq_ignore_ascii_case("false"));
    if asked && in_ci { Err(()) } else { Ok(asked) }
}

#[test]
fn rewriting_expectations_fails_in_ci() {
    assert_eq!(decide(true, Some("true")), Err(()));
    assert_eq!(decide(true, Some("1")), Err(()));
    assert_eq!(decide(true, None), Ok(true));
    assert_eq!(decide(true, Some("false")), Ok(true));
    assert_eq!(decide(false, Some("true")), Ok(false));
    assert_eq!(decide(false, None), Ok(false));
}
