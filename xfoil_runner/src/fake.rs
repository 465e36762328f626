//! A fake `xfoil` for tests of code that runs XFOIL: a bash script that speaks just enough of
//! XFOIL's dialogue (`PACC` + file names, `ALFA a` saving a point to the polar file, `INIT`,
//! `QUIT`) and runs a chosen snippet at each angle, to crash, hang, babble or write garbage
//! where a test wants it. Its polar is cl = 0.4 + 0.1 a, cd = 0.01 + 0.001 a^2 (a in degrees)
//! unless the snippet sets `cl` and `cd`.

use std::path::{Path, PathBuf};

/// Writes the fake as `dir/xfoil` (executable) and returns its path. `behaviour` is bash run
/// at each `ALFA $arg` before the point is saved; it sees `$arg` (the angle as XFOIL's script
/// writes it, `2.000000`), `$acc` (1 while the polar accumulates) and `$polar` (its file), and
/// `$init` (1 when the boundary layer was just initialised), and may set `cl` and `cd` (the
/// point saved; both unset or empty: the fake's own polar).
pub fn write_fake_xfoil(dir: &Path, behaviour: &str) -> std::io::Result<PathBuf> {
    use std::os::unix::fs::PermissionsExt;
    let path = dir.join("xfoil");
    let script = format!(
        r#"#!/bin/bash
echo "  XFOIL Version 6.99 (fake)"
acc=0; init=1
while read -r cmd arg; do
  case "$cmd" in
    PACC)
      if [ $acc = 0 ]; then
        read -r polar; read -r dump; acc=1; echo " Polar accumulation enabled"
        printf '\n   alpha    CL        CD       CDp       CM     Top_Xtr  Bot_Xtr\n  ------ -------- --------- --------- -------- -------- --------\n' > "$polar"
      else acc=0; fi ;;
    ALFA)
      echo "       a =  $arg      CL =  0.5"
      cl=""; cd=""
      {behaviour}
      was_init=$init; init=0
      if [ $acc = 1 ]; then
        awk -v a="$arg" -v cl="$cl" -v cd="$cd" 'BEGIN {{ if (cl == "") cl = 0.4 + 0.1 * a; if (cd == "") cd = 0.01 + 0.001 * a * a; printf "%8.3f %8.4f %9.5f %9.5f %8.4f %8.4f %8.4f\n", a, cl, cd, 0.005, -0.1, 0.5, 1.0 }}' >> "$polar"
      fi ;;
    INIT) init=1 ;;
    QUIT) exit 0 ;;
  esac
done
"#
    );
    std::fs::write(&path, script)?;
    std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o755))?;
    Ok(path)
}
