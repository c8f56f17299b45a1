#!/usr/bin/env python3
"""End-to-end check with an independent reader: run `cargo xtask mesh` on every built-in case,
then have Gmsh (tests/python/check_msh.py) read each .msh and compare what it finds with our
report: node and element counts, the physical groups `fluid`, `wall`, `farfield`, and a
positive scaled Jacobian on every cell. Also checks that bad input exits with status 1, one
line on stderr, and no file.

Usage: python3 tests/python/e2e.py XTASK_BINARY
Ends with the line "N passed, M failed"; exit status 1 if any check failed.
"""
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
passed, failed = 0, 0


def check(ok, what):
    global passed, failed
    if ok:
        passed += 1
    else:
        failed += 1
        print(f"FAIL {what}")


def gmsh_read(path):
    r = subprocess.run([sys.executable, os.path.join(HERE, "check_msh.py"), path],
                       capture_output=True, text=True)
    if r.returncode != 0:
        return None, r.stdout + r.stderr
    return json.loads(r.stdout.strip().splitlines()[-1]), ""


def main(xtask):
    names = [l.split()[0] for l in
             subprocess.run([xtask, "mesh", "--list"], capture_output=True, text=True,
                            check=True).stdout.splitlines() if l.strip()]
    check(len(names) >= 4, "at least four built-in cases")
    with tempfile.TemporaryDirectory() as tmp:
        for name in names:
            for extra, tag in (([], "mixed"), (["--triangles"], "tri")):
                msh = os.path.join(tmp, f"{name}-{tag}.msh")
                rep = os.path.join(tmp, f"{name}-{tag}.json")
                r = subprocess.run([xtask, "mesh", name, "--order", "1", "--quiet", "--out", msh,
                                    "--report", rep] + extra, capture_output=True, text=True)
                check(r.returncode == 0, f"{name} {tag}: xtask exit {r.returncode}: {r.stderr}")
                if r.returncode != 0:
                    continue
                report = json.load(open(rep))
                g, err = gmsh_read(msh)
                check(g is not None, f"{name} {tag}: gmsh reads the file: {err}")
                if g is None:
                    continue
                check(not g["warnings"], f"{name} {tag}: gmsh warnings {g['warnings'][:3]}")
                el = g["elements"]
                check(g["nodes"] == report["nodes"],
                      f"{name} {tag}: nodes {g['nodes']} vs report {report['nodes']}")
                tri = sum(v for k, v in el.items() if k.startswith("Triangle"))
                quad = sum(v for k, v in el.items() if k.startswith("Quadrilateral"))
                lines = sum(v for k, v in el.items() if k.startswith("Line"))
                check(tri == report["cells"]["tri"] and quad == report["cells"]["quad"],
                      f"{name} {tag}: gmsh counts tri {tri} quad {quad} vs {report['cells']}")
                check(tag != "tri" or quad == 0, f"{name}: --triangles leaves no quad")
                check(lines == sum(report["boundary_facets"].values()),
                      f"{name} {tag}: boundary lines {lines}")
                groups = {p["name"]: p["elements"] for p in g["physical_groups"]}
                check(groups.get("fluid") == tri + quad, f"{name} {tag}: fluid group {groups}")
                for role, n in report["boundary_facets"].items():
                    check(groups.get(role) == n, f"{name} {tag}: group {role} has {n} lines")
                sj = g["min_scaled_jacobian"]
                check(sj is not None and sj > 0, f"{name} {tag}: gmsh minSJ {sj} > 0")
                print(f"ok   {name:<12} {tag:<5} nodes {g['nodes']:>7}  tri {tri:>7}  "
                      f"quad {quad:>7}  gmsh minSJ {sj:.3f}  max angle "
                      f"{report['quality']['max_angle_deg']:.1f}")

        # Bad input through the real binary: exit 1, one line on stderr, no file written.
        bad = os.path.join(tmp, "bad.toml")
        with open(bad, "w") as f:
            f.write('[[loop]]\nrole = "wall"\npoints = [[0,0],[1,1],[1,0],[0,1]]\n'
                    '[[loop]]\nrole = "farfield"\ncircle = { center = [0, 0], radius = 9 }\n')
        out = os.path.join(tmp, "bad.msh")
        r = subprocess.run([xtask, "mesh", bad, "--out", out], capture_output=True, text=True)
        check(r.returncode == 1, f"bad input exits 1 (got {r.returncode})")
        check(len(r.stderr.strip().splitlines()) == 1 and "intersects itself" in r.stderr,
              f"bad input: one line naming the fault: {r.stderr!r}")
        check(not os.path.exists(out), "bad input writes no file")
        check("panicked" not in r.stderr, "no panic")
    print(f"{passed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1]))
