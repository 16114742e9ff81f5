"""tessera check's report.html in a real browser: headless Chromium, driven by Selenium, opens
the report of a failed case and checks what a reviewer uses: the wipe slider uncovers the golden, the flip
button (and the f key) swaps new and golden in place, a click shows an image at 1:1, the full-size links
reach the images, the changed scene field is listed, and the metrics are rounded. Builds its own
one-case suite (a cube at 640x360, wider than the report shows an image) in a temporary directory; no server, the page is a file.

    report_browser_test.py TESSERA_BINARY SOURCE_DIR [--screenshot FILE]

Exit 77 (ctest: skipped) with the reason when Chromium, ChromeDriver or Selenium is absent.
"""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

from browser_support import check, headless_chromium, require_browser


def main():
    binary, source = sys.argv[1], sys.argv[2]
    screenshot = sys.argv[sys.argv.index("--screenshot") + 1] if "--screenshot" in sys.argv else None
    require_browser()
    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.by import By

    work = tempfile.mkdtemp(prefix="tessera-report-test-")
    driver = None
    try:
        cube = os.path.join(source, "tests/data/osd-shapes/catmark_cube.obj")
        scene = os.path.join(work, "cube.json")
        subprocess.run([binary, "-q", "render", cube, "--resolution", "640x360", "--factor", "4", "--threads", "2",
                        "--print-scene", scene], check=True)
        suite = os.path.join(work, "suite.json")
        with open(suite, "w") as f:
            json.dump({"tessera_suite": 1, "name": "report", "golden": "golden",
                       "cases": [{"name": "cube", "scene": "cube.json", "compare": "exact"}]}, f)
        subprocess.run([binary, "-q", "check", suite, "--update", "-o", os.path.join(work, "first")], check=True)
        with open(scene) as f:
            s = json.load(f)
        s["factor"] = 2.0
        with open(scene, "w") as f:
            json.dump(s, f)
        report = os.path.join(work, "report")
        r = subprocess.run([binary, "-q", "check", suite, "-o", report], capture_output=True, text=True)
        check(r.returncode == 1, f"the changed case fails (exit {r.returncode})")

        driver = headless_chromium(f"{work}/profile", "--allow-file-access-from-files")
        driver.get("file://" + os.path.join(report, "report.html"))

        top = driver.find_element(By.CSS_SELECTOR, ".wipe img.top")
        under = driver.find_element(By.CSS_SELECTOR, ".wipe img:not(.top)")
        check(top.get_attribute("src").endswith("new/cube.png") and under.get_attribute("src").endswith(
            "golden/cube.png"), "the wipe holds the new image over the golden")
        loaded = driver.execute_script(
            "return Array.from(document.images).every(i => i.complete && i.naturalWidth > 0);")
        check(loaded, "every image of the report loads")

        # The slider: at 20 the new image is clipped to its left fifth, the golden shows on the right.
        slider = driver.find_element(By.CSS_SELECTOR, "input[type=range]")
        driver.execute_script("arguments[0].value = 20; arguments[0].dispatchEvent(new Event('input'));", slider)
        clip = driver.execute_script("return arguments[0].style.clipPath;", top)
        check(clip.replace(" ", "") == "inset(0px80%0px0px)", f"the slider clips the new image ({clip})")

        # Flip: the golden alone, then the new one again; the f key over the case does the same.
        flip = driver.find_element(By.CSS_SELECTOR, "button.flip")
        flip.click()
        check(top.value_of_css_property("visibility") == "hidden" and "golden" in flip.text,
              f"flip shows the golden ({flip.text!r})")
        ActionChains(driver).move_to_element(flip).send_keys("f").perform()
        check(top.value_of_css_property("visibility") == "visible" and "new" in flip.text,
              f"the f key flips back to the new image ({flip.text!r})")

        # 1:1: a click on the difference picture lifts the width limit; the full-size links reach files.
        diff = driver.find_element(By.CSS_SELECTOR, "img[alt=diff]")
        shown = diff.size["width"]
        diff.click()
        check(shown < 640 and "full" in diff.get_attribute("class") and diff.size["width"] >= 640,
              f"a click shows the image at 1:1 ({shown} -> {diff.size['width']} px)")
        links = [a.get_attribute("href") for a in driver.find_elements(By.PARTIAL_LINK_TEXT, "full size")]
        check(len(links) == 3 and all(os.path.exists(l[len("file://"):]) for l in links),
              f"the three full-size links name images that exist ({len(links)})")

        page = driver.find_element(By.TAG_NAME, "body").text
        check(re.search(r"factor\s+4(\.0)?\s+2(\.0)?", page) is not None, "the changed scene field is listed")
        check(re.search(r"(mean|RMS|PSNR) [0-9]*\.[0-9]{7,}", page) is None, "the metrics are rounded")
        if screenshot:
            driver.save_screenshot(screenshot)
    finally:
        if driver is not None:
            driver.quit()
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
