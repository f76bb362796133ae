"""The report pages in a real browser (Debian's Chromium, headless, through its
chromedriver): each page must load without a console error, every <math> element must
be laid out as MathML (a box of non-zero size, CSS display `math`: Chromium renders
MathML Core natively), every <svg> must hold drawing elements that cover an area, and
the screenshots must not be blank (one colour). The page itself has no script: the
checks are injected here.

    python report_browser.py OUT_DIR PAGE.html...

Screenshots go to OUT_DIR: NAME-top.png (the first screen), NAME-singular-view.png (the
screen from the singular factors on) and NAME-SECTION.png for the singular factors and
each section with a picture. Exits 1 with one line per failure.
"""

import json
import sys
import time
from pathlib import Path

from PIL import Image
from selenium import webdriver
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.common.by import By

CHROMIUM = "/usr/bin/chromium"
CHROMEDRIVER = "/usr/bin/chromedriver"

# Sizes and computed display of every <math>; drawing children and content box of
# every <svg>.
PROBE = """
const maths = [...document.querySelectorAll('math')].map(m => {
  const r = m.getBoundingClientRect();
  return [r.width, r.height, getComputedStyle(m).display, m.textContent.slice(0, 60)];
});
const svgs = [...document.querySelectorAll('svg')].map(s => {
  const r = s.getBoundingClientRect();
  const drawn = s.querySelectorAll('rect,polyline,circle,line,path').length;
  let box = [0, 0];
  try { const b = s.getBBox(); box = [b.width, b.height]; } catch (e) {}
  return [r.width, r.height, drawn, box[0], box[1]];
});
return JSON.stringify({maths, svgs});
"""


def blank(png: Path) -> bool:
    """All one colour."""
    with Image.open(png) as im:
        lo_hi = im.convert("RGB").getextrema()
    return all(lo == hi for lo, hi in lo_hi)


def main() -> int:
    out = Path(sys.argv[1])
    out.mkdir(parents=True, exist_ok=True)
    pages = [Path(p).resolve() for p in sys.argv[2:]]
    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for arg in ["--headless=new", "--no-sandbox", "--disable-gpu", "--window-size=1280,1000",
                "--hide-scrollbars", "--disable-dev-shm-usage"]:
        options.add_argument(arg)
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    driver = webdriver.Chrome(service=Service(CHROMEDRIVER), options=options)
    failures = []
    try:
        for page in pages:
            name = page.stem
            start = time.monotonic()
            driver.get(page.as_uri())
            while driver.execute_script("return document.readyState") != "complete":
                time.sleep(0.05)
            for entry in driver.get_log("browser"):
                if entry.get("level") == "SEVERE":
                    failures.append(f"{name}: console error: {entry.get('message')}")
            probe = json.loads(driver.execute_script(PROBE))
            maths, svgs = probe["maths"], probe["svgs"]
            if not maths:
                failures.append(f"{name}: no <math> element")
            for w, h, display, text in maths:
                if w <= 0 or h <= 0:
                    failures.append(f"{name}: <math> without a layout box: {text!r}")
                if "math" not in display:
                    failures.append(f"{name}: <math> displayed as {display!r}, not MathML: {text!r}")
            if not svgs:
                failures.append(f"{name}: no <svg> element")
            for i, (w, h, drawn, bw, bh) in enumerate(svgs):
                if w <= 0 or h <= 0 or drawn == 0 or bw <= 0 or bh <= 0:
                    failures.append(
                        f"{name}: <svg> #{i + 1} is empty ({w}x{h} px, {drawn} drawing "
                        f"elements, content {bw}x{bh})")
            shots = [out / f"{name}-top.png"]
            driver.save_screenshot(str(shots[0]))
            # The singular factors and the map under them, one screen (the README's).
            driver.execute_script("document.getElementById('singularities').scrollIntoView()")
            shots.append(out / f"{name}-singular-view.png")
            driver.save_screenshot(str(shots[-1]))
            for sid in ["singularities", "singularity-map", "stick-figures", "trajectory",
                        "reachability"]:
                found = driver.find_elements(By.ID, sid)
                if found:
                    shot = out / f"{name}-{sid}.png"
                    found[0].screenshot(str(shot))
                    shots.append(shot)
            for shot in shots:
                if blank(shot):
                    failures.append(f"{name}: blank screenshot {shot.name}")
            print(f"{name}: {len(maths)} <math>, {len(svgs)} <svg>, {len(shots)} screenshots, "
                  f"{time.monotonic() - start:.1f} s")
    finally:
        driver.quit()
    for f in failures:
        print(f"FAIL {f}", file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
