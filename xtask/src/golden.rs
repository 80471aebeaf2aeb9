//! `cargo xtask golden`: run the firmware's smoke scenario on the host and write the golden
//! commands the firmware compares itself against (`onboard-spec/src/golden.rs`).

use std::path::Path;

use guidance_core::{Fixed, Scalar};
use onboard_spec::scenario::{self, Row, SAMPLES, SEQUENCES};

fn rows<S: Scalar>() -> Result<[[Row<S>; SAMPLES]; SEQUENCES], String> {
    let zero = Row {
        alpha_rad: S::ZERO,
        sigma_rad: S::ZERO,
        cmd_alpha_rad: S::ZERO,
        cmd_sigma_rad: S::ZERO,
    };
    let mut out = [[zero; SAMPLES]; SEQUENCES];
    scenario::run(&mut out).map_err(|e| format!("smoke scenario failed on the host: {e}"))?;
    Ok(out)
}

fn table<S: Scalar>(
    name: &str,
    ty: &str,
    rows: &[[Row<S>; SAMPLES]; SEQUENCES],
    fmt: impl Fn(S) -> String,
) -> String {
    let mut s =
        format!("/// Host-computed rows (alpha, sigma, command alpha, command sigma) [{ty}].\n");
    s += &format!("pub const {name}: [[[{ty}; 4]; {SAMPLES}]; {SEQUENCES}] = [\n");
    for seq in rows {
        s += "    [\n";
        for r in seq {
            let v = [r.alpha_rad, r.sigma_rad, r.cmd_alpha_rad, r.cmd_sigma_rad].map(&fmt);
            s += &format!("        [{}],\n", v.join(", "));
        }
        s += "    ],\n";
    }
    s += "];\n";
    s
}

/// The text of `golden.rs` as the current host code computes it.
pub fn render() -> Result<String, String> {
    let f32_rows = rows::<f32>()?;
    let fixed_rows = rows::<Fixed>()?;
    let mut text = String::from(
        "//! Golden guidance outputs computed on the host by `cargo xtask golden` from\n\
         //! `scenario.rs`. Generated: do not edit. The workspace test\n\
         //! `firmware_golden_is_current` fails when this file is stale.\n\n",
    );
    text += &table("F32", "f32", &f32_rows, |v: f32| format!("{v:?}"));
    text += "\n";
    text += &table("FIXED_BITS", "i64", &fixed_rows, |v: Fixed| {
        format!("{}", v.to_bits())
    });
    Ok(text)
}

/// Write `onboard-spec/src/golden.rs` atomically.
pub fn write(root: &Path) -> Result<(), String> {
    let text = render()?;
    let path = root.join("onboard-spec").join("src").join("golden.rs");
    let tmp = path.with_extension("rs.tmp");
    std::fs::write(&tmp, text).map_err(|e| format!("{}: {e}", tmp.display()))?;
    std::fs::rename(&tmp, &path).map_err(|e| format!("{}: {e}", path.display()))?;
    println!("xtask: wrote {}", path.display());
    Ok(())
}
