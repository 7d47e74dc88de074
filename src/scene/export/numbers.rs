//! Real numbers as the exchange formats write them: the shortest text that
//! reads back as the same `f64`, always with a decimal point and an
//! upper-case exponent (ISO 10303-21 §6.3.2, IGES 5.3 §2.2.2.4).

/// `x` (finite) as `1.5`, `-2.`, `1.E-07`, `3.25E+12`.
pub fn real(x: f64) -> String {
    let s = format!("{x:?}");
    let (mantissa, exp) = match s.split_once('e') {
        Some((m, e)) => (m.to_string(), Some(e.to_string())),
        None => (s, None),
    };
    let mantissa = if mantissa.contains('.') {
        mantissa.trim_end_matches('0').to_string()
    } else {
        format!("{mantissa}.")
    };
    match exp {
        Some(e) => format!("{mantissa}E{e}"),
        None => mantissa,
    }
}

#[cfg(test)]
mod tests {
    use super::real;

    #[test]
    fn reals_have_a_point_and_read_back_exactly() {
        for (x, want) in [
            (1.0, "1."),
            (-2.5, "-2.5"),
            (1e-7, "1.E-7"),
            (0.0, "0."),
            (123456.0, "123456."),
            (1.5e300, "1.5E300"),
        ] {
            assert_eq!(real(x), want);
        }
        for x in [0.1, 1.0 / 3.0, -7.25e-12, 6.02e23, f64::MIN_POSITIVE] {
            let s = real(x);
            assert!(s.contains('.'), "{s}");
            assert_eq!(s.parse::<f64>().unwrap(), x, "{s}");
        }
    }
}
