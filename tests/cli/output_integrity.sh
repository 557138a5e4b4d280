#!/usr/bin/env bash
# Outputs a user can trust: every output target is checked before the solve
# (missing directory, a directory as target, a plot name that is neither .svg nor .png, no
# gnuplot or no pngcairo terminal, the same file twice) with one line and exit 2 and nothing
# written; a failed run leaves no earlier output behind; symbolic links (/dev/stdout), FIFOs and
# devices are never replaced; "-" is standard output; --plot x.png is a real PNG; the XLSX
# summary holds numbers as numbers with the header frozen and column widths set.
set -uo pipefail
source "$(dirname "$0")/lib/common.sh" "$@"

run=(solve --from A6 --to A7 --time 110)

# Checked before solving: nothing written, not even the outputs that could have been.
expect_error "--plot" "${run[@]}" --json ok.json --plot outdir --csv ok.csv
mkdir adir
expect_error "is a directory" "${run[@]}" --json ok.json --csv adir
expect_error "does not exist" "${run[@]}" --json ok.json --csv nodir/x.csv
expect_error "--plot" "${run[@]}" --json ok.json --plot x.pdf
expect_error "twice" "${run[@]}" --json same.json --csv ./same.json
expect_error "twice" "${run[@]}" --json same.json --csv adir/../same.json
expect_error "twice" "${run[@]}" --json - --csv -
expect_error "--xlsx" "${run[@]}" --xlsx -

# Never replace what is not a regular file.
echo kept > target.json
ln -s target.json link.json
expect_error "symbolic link" "${run[@]}" --json link.json
[ -L link.json ] && [ "$(cat target.json)" = kept ] || { echo "FAIL: link replaced"; fail=1; }
mkfifo fifo
expect_error "not a regular file" "${run[@]}" --csv fifo
[ -p fifo ] || { echo "FAIL: FIFO replaced"; fail=1; }
link_before=$(readlink /dev/stdout)
"$ecorail" "${run[@]}" --json /dev/stdout > /dev/null 2> err.txt
code=$?
[ "$code" -eq 2 ] || { echo "FAIL: --json /dev/stdout exit $code"; fail=1; }
[ -L /dev/stdout ] && [ "$(readlink /dev/stdout)" = "$link_before" ] ||
  { echo "FAIL: /dev/stdout was replaced"; fail=1; }
"$ecorail" "${run[@]}" --csv /dev/null > /dev/null 2> err.txt
[ $? -eq 2 ] && [ -c /dev/null ] || { echo "FAIL: /dev/null not refused or replaced"; fail=1; }

# "-" is standard output (the CSV follows the report), and no file "-" appears.
"$ecorail" "${run[@]}" --csv - > stdout.csv 2> err.txt || { echo "FAIL: --csv - failed"; fail=1; }
grep -q "^time_hms,speed_cm_s,speed_kmh" stdout.csv || { echo "FAIL: no CSV on stdout"; fail=1; }
[ ! -e ./- ] || { echo "FAIL: a file named - was written"; fail=1; }
rm -f stdout.csv err.txt

# A missing gnuplot, or one without the pngcairo terminal, is refused before solving.
mkdir fakebin
cat > fakebin/gnuplot <<'EOF'
#!/bin/sh
case "$*" in *pngcairo*) echo "unknown or ambiguous terminal type" >&2; exit 1;; esac
exec /usr/bin/gnuplot "$@"
EOF
chmod +x fakebin/gnuplot
real_ecorail=$ecorail
printf '#!/bin/sh\nPATH="%s" exec "%s" "$@"\n' "$PWD/fakebin" "$real_ecorail" > fake_gnuplot.sh
printf '#!/bin/sh\nPATH=/nonexistent exec "%s" "$@"\n' "$real_ecorail" > no_gnuplot.sh
chmod +x fake_gnuplot.sh no_gnuplot.sh
ecorail="$PWD/fake_gnuplot.sh"
expect_error "pngcairo" "${run[@]}" --json ok.json --plot x.png
ecorail="$PWD/no_gnuplot.sh"
expect_error "gnuplot is not installed" "${run[@]}" --json ok.json --plot x.svg
ecorail=$real_ecorail
rm -rf fakebin fake_gnuplot.sh no_gnuplot.sh

if command -v gnuplot > /dev/null; then
  # A PNG is a PNG, an SVG an SVG.
  "$ecorail" solve --from A6 --to A8 --time 220 --dwell A7=45 --plot j.png --xlsx j.xlsx \
    > /dev/null 2> err.txt || { echo "FAIL: journey plot"; cat err.txt; fail=1; }
  [ "$(head -c 8 j.png | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ] ||
    { echo "FAIL: j.png is not a PNG"; fail=1; }
  "$ecorail" "${run[@]}" --plot s.svg > /dev/null && grep -q "<svg" s.svg ||
    { echo "FAIL: s.svg is not an SVG"; fail=1; }

  # The XLSX: numbers on the summary sheet are numeric cells, header rows frozen, widths set.
  python3 - j.xlsx <<'PY' || fail=1
import re, sys, zipfile
z = zipfile.ZipFile(sys.argv[1])
book = z.read("xl/workbook.xml").decode()
names = re.findall(r'<sheet name="([^"]+)"', book)
assert names == ["profile", "summary"], names
strings = re.findall(r"<t[^>]*>([^<]*)</t>", z.read("xl/sharedStrings.xml").decode())
for i, name in enumerate(names, start=1):
    sheet = z.read(f"xl/worksheets/sheet{i}.xml").decode()
    assert re.search(r'<pane [^>]*ySplit="1"[^>]*state="frozen"', sheet), f"{name}: header not frozen"
    assert re.search(r"<cols>.*<col [^>]*width=", sheet, re.S), f"{name}: no column widths"
summary = z.read("xl/worksheets/sheet2.xml").decode()
values = {}
for row in re.findall(r"<row [^>]*>(.*?)</row>", summary, re.S):
    cells = re.findall(r'<c r="([A-Z]+)\d+"([^>]*)>(?:<v>([^<]*)</v>)?', row)
    if len(cells) < 2:
        continue
    key = strings[int(cells[0][2])]
    attrs, v = cells[1][1], cells[1][2]
    values[key] = float(v) if 't="s"' not in attrs else strings[int(v)]
energy = [k for k in values if "energy" in k and k.endswith("_kJ")]
assert energy, f"no energy rows in summary: {list(values)}"
for k in energy + [k for k in values if k.endswith("_s")]:
    assert isinstance(values[k], float), f"summary {k} stored as text: {values[k]!r}"
print("xlsx ok:", len(values), "summary rows,", len(energy), "energies numeric")
PY
fi

[ "$fail" -eq 0 ] && echo "output_integrity: ok"
exit "$fail"
