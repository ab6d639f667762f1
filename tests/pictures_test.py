#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""keyrot's pictures as a person sees them: rendered by headless Chromium.

For `keyrot plot` (--rep angle, euler and quat, --method slerp and nlerp,
--speed), `compare --plot` and `reduce --plot`:
- xmllint validates each picture against the SVG 1.1 DTD, and the same
  input gives the same bytes;
- to a viewer that prefers a dark page, the background is dark and the
  lines take their lighter colours;
- the screenshot is not blank, and curves land where the data says: the
  pixel at a time and value (placed by the axis's own tick labels) holds the
  curve's colour, the values computed here (slerp's and nlerp's angles by
  their formulas, the keys kept by reduce as its output file holds them);
- a noisy track of 100,000 frames stays under 400 KB;
- bad input (no -o, an unwritable target, a --track that matches nothing,
  --plot -) is one line, exit 2, nothing written;
- the README's pictures (docs/pictures) are what keyrot draws today:
  `pictures_test.py KEYROT DATA PICTURES --update` writes them again.

Usage: pictures_test.py KEYROT DATA_DIR PICTURES_DIR [--update]. Exit 0
when all pass, 1 otherwise.
"""
import csv
import math
import os
import shutil
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

try:
    from PIL import Image
except ImportError:
    print("pictures_test: python3-pil is missing (bash .ci/deps test installs it)")
    sys.exit(1)

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "support"))
from tally import check, summary  # noqa: E402

KEYROT = os.path.abspath(sys.argv[1])
DATA = os.path.abspath(sys.argv[2])
PICTURES = os.path.abspath(sys.argv[3])
UPDATE = "--update" in sys.argv[4:]
SVG_DTD = "/usr/share/xml/w3c-sgml-lib/schema/dtd/REC-SVG11-20110816/svg11.dtd"
NS = "{http://www.w3.org/2000/svg}"
# The palette's light colours: a quaternion's w x y z (or Euler angles in
# order), the speed, the tolerance line, failing rows.
BLUE, VERMILLION, GREEN, PURPLE = (0x00, 0x72, 0xB2), (0xD5, 0x5E, 0x00), (0x00, 0x9E, 0x73), (0xCC, 0x79, 0xA7)
ORANGE, GREY = (0xE6, 0x9F, 0x00), (0x76, 0x76, 0x76)
def keyrot(*args, stdin=None):
    p = subprocess.run([KEYROT, *args], input=stdin, capture_output=True, text=True)
    return p.returncode, p.stdout, p.stderr


for tool in ("chromium", "xmllint"):
    if not shutil.which(tool):
        print(f"pictures_test: {tool} is missing (bash .ci/deps test installs it)")
        sys.exit(1)
if not os.path.exists(SVG_DTD):
    print("pictures_test: the SVG 1.1 DTD is missing (w3c-sgml-lib; bash .ci/deps test installs it)")
    sys.exit(1)

work = tempfile.mkdtemp(prefix="keyrot-pictures-")


def path(name):
    return os.path.join(work, name)


class Panel:
    """A panel of a picture: its title, and its axes as its tick labels place them."""

    def __init__(self, group):
        self.title = ""
        xs, ys = [], []
        for text in group.iter(NS + "text"):
            content = "".join(text.itertext())
            if text.get("font-weight") == "bold":
                self.title = content
                continue
            try:
                value = float(content)
            except ValueError:
                continue
            if text.get("text-anchor") == "end":  # a y tick label: its baseline 4 px under the tick
                ys.append((value, float(text.get("y")) - 4))
            elif text.get("text-anchor") == "middle":
                xs.append((value, float(text.get("x"))))
        self.x = self.fit(xs)
        self.y = self.fit(ys)

    @staticmethod
    def fit(pairs):
        (v0, p0), (v1, p1) = pairs[0], pairs[-1]
        return lambda v: p0 + (v - v0) * (p1 - p0) / (v1 - v0)


def panels_of(svg_path):
    root = ET.parse(svg_path).getroot()
    return [Panel(g) for g in root.iter(NS + "g") if g.get("class") == "panel"]


def size_of(svg_path):
    root = ET.parse(svg_path).getroot()
    return int(float(root.get("width"))), int(float(root.get("height")))


def render(svg_path, dark=False):
    """The picture as Chromium shows it, at one pixel a unit (`dark`: to a viewer that prefers dark)."""
    png = svg_path + (".dark.png" if dark else ".png")
    width, height = size_of(svg_path)
    scheme = ["--force-dark-mode", "--blink-settings=preferredColorScheme=0"] if dark else []
    subprocess.run(["chromium", "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
                    "--force-device-scale-factor=1", f"--user-data-dir={path('chromium')}", *scheme,
                    f"--window-size={width},{height}", f"--screenshot={png}", "file://" + svg_path],
                   capture_output=True, timeout=120)
    return Image.open(png).convert("RGB")


def near(c, want, slack=70):
    return sum((a - b) ** 2 for a, b in zip(c, want)) <= slack * slack


def colour_at(image, x, y, want, reach=2):
    """Whether a pixel within `reach` of (x, y) has colour `want` (anti-aliasing aside)."""
    for dx in range(-reach, reach + 1):
        for dy in range(-reach, reach + 1):
            px, py = round(x) + dx, round(y) + dy
            if 0 <= px < image.width and 0 <= py < image.height and near(image.getpixel((px, py)), want):
                return True
    return False


def valid_and_seen(svg_path, what):
    """xmllint against the DTD, a screenshot that is not blank; returns the screenshot."""
    p = subprocess.run(["xmllint", "--noout", "--dtdvalid", SVG_DTD, svg_path], capture_output=True, text=True)
    check(p.returncode == 0, f"{what}: valid SVG 1.1 {p.stderr.strip()[:300]}")
    image = render(svg_path)
    width, height = size_of(svg_path)
    check(image.size == (width, height), f"{what}: rendered at its size {image.size}")
    background = image.getpixel((1, 1))
    inked = sum(1 for x in range(0, image.width, 3) for y in range(0, image.height, 3)
                if image.getpixel((x, y)) != background)
    check(inked > image.width * image.height / 9 * 0.02, f"{what}: not blank ({inked} inked samples)")
    return image


def same_bytes(args, svg_path, what):
    again = svg_path + ".again.svg"
    out_at = args.index("--plot") + 1 if "--plot" in args else args.index("-o") + 1
    rerun = list(args)
    rerun[out_at] = again
    keyrot(*rerun)
    with open(svg_path, "rb") as a, open(again, "rb") as b:
        check(a.read() == b.read(), f"{what}: the same bytes for the same input")


def write_csv(name, header, rows):
    with open(path(name), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        w.writerows(rows)
    return path(name)


# A turn of 170 degrees about z in 2 s: slerp turns 85 deg/s; nlerp, ahead
# and behind, by the formula of the normalised lerp.
turn = write_csv("turn.csv", ["time", "ax", "ay", "az", "angle"], [[0, 0, 0, 1, 0], [2, 0, 0, 1, 170]])


def slerp_angle(t):
    return 85 * t


def nlerp_angle(t):
    h, half = t / 2, math.radians(85)
    return math.degrees(2 * math.atan2(h * math.sin(half), (1 - h) + h * math.cos(half)))


for how, angle in (("slerp", slerp_angle), ("nlerp", nlerp_angle)):
    svg = path(f"turn-{how}.svg")
    args = ["plot", turn, "--rep", "angle", "--method", how, "-o", svg]
    status, out, err = keyrot(*args)
    check(status == 0 and out == "" and err == "", f"plot --method {how}: exit 0, quiet ({err.strip()})")
    image = valid_and_seen(svg, f"plot --method {how}")
    same_bytes(args, svg, f"plot --method {how}")
    [panel] = panels_of(svg)
    check(panel.title == turn, f"plot --method {how}: titled by its file (an unnamed track): {panel.title}")
    for t in (0.25, 0.5, 1.0, 1.5, 1.75):
        check(colour_at(image, panel.x(t), panel.y(angle(t)), BLUE),
              f"plot --method {how}: the curve at {t} s is at {angle(t):.2f} deg")
    other = nlerp_angle if how == "slerp" else slerp_angle
    check(not colour_at(image, panel.x(0.5), panel.y(other(0.5)), BLUE, reach=1),
          f"plot --method {how}: not at the other method's {other(0.5):.2f} deg at 0.5 s")
    for t, a in ((0, 0), (2, 170)):
        check(colour_at(image, panel.x(t), panel.y(a), BLUE, reach=0), f"plot --method {how}: key at {t} s marked")

# Euler angles and the speed below them: Z turns at 85 deg/s, Y and X stay 0.
svg = path("turn-euler.svg")
status, _, err = keyrot("plot", turn, "--euler", "ZYX", "--speed", "-o", svg)
check(status == 0, f"plot --euler ZYX --speed: exit 0 ({err.strip()})")
image = valid_and_seen(svg, "plot --euler ZYX --speed")
curves, speed = panels_of(svg)
for t in (0.3, 1.1, 1.9):
    check(colour_at(image, curves.x(t), curves.y(85 * t), BLUE), f"plot --euler: Z at {t} s is {85 * t:.1f} deg")
    check(colour_at(image, curves.x(t), curves.y(0), GREEN) or colour_at(image, curves.x(t), curves.y(0), VERMILLION),
          f"plot --euler: Y and X at 0 at {t} s")
    check(colour_at(image, speed.x(t), speed.y(85), ORANGE), f"plot --speed: 85 deg/s at {t} s")

# Quaternion components of walk.csv's knee: its keys, as convert writes them.
svg = path("walk.svg")
status, _, err = keyrot("plot", os.path.join(DATA, "walk.csv"), "--track", "kn*", "-o", svg)
check(status == 0, f"plot --track 'kn*': exit 0 ({err.strip()})")
image = valid_and_seen(svg, "plot walk.csv --track kn*")
panels = panels_of(svg)
check([p.title for p in panels] == ["knee"], f"plot --track 'kn*': the knee alone: {[p.title for p in panels]}")
_, keys, _ = keyrot("convert", os.path.join(DATA, "walk.csv"), "--rep", "quat", "--to", "csv")
for row in csv.DictReader(keys.splitlines()):
    if row["track"] != "knee":
        continue
    t = float(row["time"])
    w, x = float(row["qw"]), float(row["qx"])
    sign = 1 if w >= 0 else -1  # the curve keeps the sign of the first key, which is w > 0 here
    # (where w and x cross, x is drawn over w)
    crossing = abs(w - x) < 0.03
    check(colour_at(image, panels[0].x(t), panels[0].y(sign * w), BLUE, reach=1)
          or (crossing and colour_at(image, panels[0].x(t), panels[0].y(sign * w), VERMILLION, reach=1)),
          f"plot: knee's w at {t} s is {w}")
    check(colour_at(image, panels[0].x(t), panels[0].y(sign * x), VERMILLION, reach=1), f"plot: knee's x at {t} s is {x}")

# compare --plot: one row of the answer 3 degrees off, the tolerance 1 degree.
key = path("key.csv")
keyrot("resample", turn, "--fps", "10", "-o", key)
with open(key) as f:
    rows = list(csv.reader(f))
header, body = rows[0], rows[1:]
angle_col = header.index("angle")
body[7][angle_col] = str(float(body[7][angle_col]) + 3)
answer = write_csv("answer.csv", header, body)
bad_time = float(body[7][header.index("time")])
svg = path("diff.svg")
args = ["compare", key, answer, "--tol", "1", "--plot", svg]
status, out, err = keyrot(*args)
check(status == 1, f"compare --plot: exit 1 for the failing row ({status})")
check("1 failed" in out, f"compare --plot: the summary as ever ({out.strip()})")
image = valid_and_seen(svg, "compare --plot")
same_bytes(args, svg, "compare --plot")
[panel] = panels_of(svg)
check(colour_at(image, panel.x(bad_time), panel.y(3), VERMILLION), f"compare --plot: the failing row marked at {bad_time} s, 3 deg")
check(colour_at(image, panel.x(0.2), panel.y(1), GREY, reach=1), "compare --plot: the tolerance line at 1 deg")
check(colour_at(image, panel.x(1.5), panel.y(0), BLUE, reach=1), "compare --plot: no difference at 1.5 s")
# To a viewer that prefers dark: a dark background, and the lighter variants of the colours.
dark = render(svg, dark=True)
check(sum(dark.getpixel((2, 2))) < 150, f"compare --plot, dark: a dark background {dark.getpixel((2, 2))}")
check(colour_at(dark, panel.x(bad_time), panel.y(3), (0xE8, 0x74, 0x3B)), "compare --plot, dark: the failing row in light vermillion")
check(colour_at(dark, panel.x(1.5), panel.y(0), (0x56, 0xB4, 0xE9), reach=1), "compare --plot, dark: the curve in sky blue")

# reduce --plot: the kept keys marked where reduce's output has them; the
# replay's error under the tolerance line, and reaching near it.
dense = path("dense.csv")
keyrot("resample", os.path.join(DATA, "walk.csv"), "--method", "squad", "--fps", "120", "-o", dense)
kept_csv, svg = path("kept.csv"), path("kept.svg")
args = ["reduce", dense, "--tol", "0.05", "-o", kept_csv, "--plot", svg]
status, _, err = keyrot(*args)
check(status == 0 and "keys ->" in err, f"reduce --plot: exit 0, summaries as ever ({err.splitlines()[0]})")
image = valid_and_seen(svg, "reduce --plot")
same_bytes(args, svg, "reduce --plot")
panels = panels_of(svg)
check([p.title for p in panels] == ["hip", "hip: error of the kept keys' replay", "knee",
                                    "knee: error of the kept keys' replay"],
      f"reduce --plot: a rotation and an error panel per track: {[p.title for p in panels]}")
with open(kept_csv) as f:
    kept = [r for r in csv.DictReader(f)]
for track, rotation, error in (("hip", panels[0], panels[1]), ("knee", panels[2], panels[3])):
    rows = [r for r in kept if r["track"] == track]
    # (where w and x cross, x's marks are drawn over w's)
    def marked_on_w(r):
        x, y = rotation.x(float(r["time"])), rotation.y(float(r["qw"]))
        crossing = abs(float(r["qw"]) - float(r["qx"])) < 0.03
        return colour_at(image, x, y, BLUE, reach=1) or (crossing and colour_at(image, x, y, VERMILLION, reach=1))

    marked = sum(marked_on_w(r) for r in rows)
    check(marked == len(rows), f"reduce --plot: {track}'s {len(rows)} kept keys marked on w ({marked})")
    top = error.y(0.05)
    over = [(x, y) for x in range(round(error.x(0)), round(error.x(1)))
            for y in range(round(error.y(0.06)), round(top) - 2) if near(image.getpixel((x, y)), BLUE, 40)]
    check(not over, f"reduce --plot: {track}'s replay error under the tolerance line ({over[:3]})")
    reach = any(colour_at(image, x, top + 2, BLUE, reach=1) for x in range(round(error.x(0)), round(error.x(1)), 2))
    check(reach, f"reduce --plot: {track}'s replay error reaches near the tolerance")

# Several answers, several inputs: each one's panels in turn, titled by its file.
svg = path("answers.svg")
status, _, _ = keyrot("compare", key, answer, key, "--tol", "1", "--plot", svg)
titles = [p.title for p in panels_of(svg)]
check(status == 1 and titles == [answer + ": rotation difference", key + ": rotation difference"],
      f"compare --plot, two answers: a panel each ({titles})")
svg = path("batch.svg")
status, _, _ = keyrot("reduce", dense, turn, "--tol", "0.1", "--output-dir", path("kept"), "--plot", svg)
titles = [p.title for p in panels_of(svg)]
check(status == 0 and titles == [dense + ": hip", dense + ": hip: error of the kept keys' replay", dense + ": knee",
                                 dense + ": knee: error of the kept keys' replay", turn,
                                 turn + ": error of the kept keys' replay"],
      f"reduce --plot, two inputs: each one's tracks in turn ({titles})")

# Size: a noisy take of 100,000 frames.
noisy = path("noisy.csv")
with open(noisy, "w") as f:
    f.write("time,ax,ay,az,angle\n")
    for i in range(100000):
        t = i / 120
        f.write(f"{t},{math.sin(t)},{math.cos(1.3 * t)},1,{40 * math.sin(t / 7) + 3 * math.sin(i * 2.1)}\n")
svg = path("noisy.svg")
status, _, err = keyrot("plot", noisy, "--speed", "-o", svg)
size = os.path.getsize(svg) if status == 0 else 0
check(status == 0 and 0 < size < 400_000, f"plot: 100,000 noisy frames with their speed in {size} bytes")
valid_and_seen(svg, "plot of 100,000 noisy frames")

# Bad input: one line, exit 2, nothing written.
for what, args, target in (
        ("no -o", ["plot", turn], None),
        ("an unwritable target", ["plot", turn, "-o", path("missing/dir/x.svg")], path("missing/dir/x.svg")),
        ("a --track that matches nothing", ["plot", turn, "--track", "hip", "-o", path("none.svg")], path("none.svg")),
        ("compare --plot into a missing folder", ["compare", key, answer, "--plot", path("missing/d.svg")],
         path("missing/d.svg")),
        ("reduce --plot -", ["reduce", dense, "--tol", "1", "-o", path("r.csv"), "--plot", "-"], path("r.csv")),
        ("reduce --plot into a missing folder", ["reduce", dense, "--tol", "1", "-o", path("r.csv"), "--plot",
                                                path("missing/k.svg")], path("r.csv")),
        ("plot --rep euler without a sequence", ["plot", turn, "--rep", "euler", "-o", path("e.svg")], path("e.svg"))):
    status, out, err = keyrot(*args)
    one_line = err.count("\n") == 1 and err.startswith("keyrot: ")
    check(status == 2 and one_line and out == "" and not (target and os.path.exists(target)),
          f"{what}: one line, exit 2, nothing written ({status}, {err.strip()})")

status, out, err = keyrot("plot", "-", "--from", "csv", "-o", path("empty.svg"), stdin="")
check(status == 2 and err.count("\n") == 1 and not os.path.exists(path("empty.svg")),
      f"an empty input: one line, exit 2, nothing written ({err.strip()})")

# The README's pictures, as keyrot draws them today.
walk = os.path.join(DATA, "walk.csv")
w30, w30s, w120 = path("walk30.csv"), path("walk30_squad.csv"), path("walk120.csv")
keyrot("resample", walk, "--fps", "30", "-o", w30)
keyrot("resample", walk, "--fps", "30", "--method", "squad", "-o", w30s)
keyrot("resample", walk, "--fps", "120", "--method", "squad", "-o", w120)
readme = {
    "plot.svg": ["plot", walk, "--track", "knee", "--method", "squad", "--speed"],
    "compare.svg": ["compare", w30, w30s, "--tol", "0.5"],
    "reduce.svg": ["reduce", w120, "--tol", "0.05", "-o", path("walk_kept.csv")],
}
for name, args in readme.items():
    drawn = path("readme-" + name)
    keyrot(*args, *(["-o", drawn] if args[0] == "plot" else ["--plot", drawn]))
    target = os.path.join(PICTURES, name)
    if UPDATE:
        shutil.copyfile(drawn, target)
        print(f"wrote {target}")
        continue
    with open(drawn, "rb") as a:
        fresh = a.read()
    current = open(target, "rb").read() if os.path.exists(target) else b""
    check(fresh == current, f"docs/pictures/{name} is what keyrot draws (else: pictures_test.py ... --update)")

shutil.rmtree(work)
sys.exit(summary("pictures_test"))
