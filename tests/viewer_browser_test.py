"""tessera view in a real browser: headless Chromium, driven by Selenium, loads the page a real
`tessera view` serves, drags to orbit, changes the view mode, clicks a patch, and checks that the frame
changed, that the pick names the patch the server's id buffer has under that pixel, and that the command
the page shows gives the same bytes as the frame on screen. Starts and stops its own server (127.0.0.1,
a free port) and browser.

    viewer_browser_test.py TESSERA_BINARY SOURCE_DIR [--screenshot FILE]

Exit 77 (ctest: skipped) with the reason when Chromium, ChromeDriver or Selenium is absent.
"""
import base64
import os
import shlex
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import urllib.parse
import urllib.request

from browser_support import check, fail, headless_chromium, require_browser


def main():
    binary, source = sys.argv[1], sys.argv[2]
    screenshot = sys.argv[sys.argv.index("--screenshot") + 1] if "--screenshot" in sys.argv else None
    require_browser()
    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.by import By
    from selenium.webdriver.support.ui import Select, WebDriverWait

    frog = os.path.join(source, "tests/data/sdk-cages/monsterfrog_mapped_00.obj")
    dds = os.path.join(source, "tests/data/sdk-cages/monsterfrog.dds")
    work = tempfile.mkdtemp(prefix="tessera-viewer-test-")
    server = subprocess.Popen(
        [binary, "view", frog, "--displacement", dds, "--displacement-channel", "A", "--resolution", "640x360",
         "--port", "0", "--threads", "2"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    driver = None
    try:
        url = server.stdout.readline().strip()
        check(url.startswith("http://127.0.0.1:"), f"the server prints its loopback URL ({url!r})")

        def get(path):
            with urllib.request.urlopen(url + path, timeout=60) as r:
                return r.read()

        driver = headless_chromium(f"{work}/profile")
        driver.set_script_timeout(60)
        driver.get(url)
        wait = WebDriverWait(driver, 90, poll_frequency=0.1)
        frame = driver.find_element(By.ID, "frame")

        def ready_with(predicate=lambda q: True):
            wait.until(lambda d: frame.get_attribute("data-state") == "ready"
                       and predicate(frame.get_attribute("data-query") or ""))
            return frame.get_attribute("data-query") or ""

        def shown_bytes():
            data = driver.execute_async_script(
                "const done = arguments[arguments.length - 1];"
                "fetch(document.getElementById('frame').src).then(r => r.arrayBuffer()).then(b => {"
                "  let s = ''; const u = new Uint8Array(b);"
                "  for (let i = 0; i < u.length; i += 8192) s += String.fromCharCode(...u.subarray(i, i + 8192));"
                "  done(btoa(s)); });")
            return base64.b64decode(data)

        first_query = ready_with()
        first = shown_bytes()
        check(first[:8] == b"\x89PNG\r\n\x1a\n", f"the first frame is a PNG ({len(first)} bytes)")

        # Orbit: a drag across the frame.
        ActionChains(driver).move_to_element(frame).click_and_hold().move_by_offset(60, 0).move_by_offset(
            60, 10).release().perform()
        orbit_query = ready_with(lambda q: "camera-position" in q)
        orbited = shown_bytes()
        check(orbited != first, f"dragging orbits the camera and the frame changes ({orbit_query})")

        # The view mode.
        Select(driver.find_element(By.ID, "view")).select_by_value("patch-type")
        view_query = ready_with(lambda q: "view=patch-type" in q)
        shown = shown_bytes()
        check(shown != orbited, "the patch-type view replaces the shaded frame")

        # A click on the middle of the frame picks the patch under it.
        ActionChains(driver).move_to_element(frame).click().perform()
        pick = driver.find_element(By.ID, "pick")
        wait.until(lambda d: pick.get_attribute("data-pixel"))
        x, y = map(int, pick.get_attribute("data-pixel").split(","))
        face = pick.get_attribute("data-face")
        check(face != "", f"the click at pixel ({x}, {y}) picks a patch (face {face})")
        import json
        server_pick = json.loads(get(f"api/pick?{view_query}&x={x}&y={y}"))
        check(server_pick["patch"] is not None and str(server_pick["patch"]["face"]) == face,
              f"the page names the patch the server's id buffer has there (face {face})")
        check(str(server_pick["patch"]["face"]) in pick.text, "the pick panel shows the face")

        # The command on the page gives the bytes on screen.
        command = driver.find_element(By.ID, "command").text
        wait.until(lambda d: "patch-type" in driver.find_element(By.ID, "command").text)
        command = driver.find_element(By.ID, "command").text
        words = shlex.split(command)
        check(words[:2] == ["tessera", "render"] and words[-2] == "-o", f"the page shows a render command")
        out = os.path.join(work, "again.png")
        words = [binary] + words[1:-1] + [out]
        subprocess.run(words + ["-q"], check=True)
        with open(out, "rb") as f:
            again = f.read()
        check(again == shown, "running the page's command gives the frame's bytes")
        # The address keeps the settings of the frame on screen, and a link restores them.
        wait.until(lambda d: "view=patch-type" in d.execute_script("return location.search"))
        link = driver.execute_script("return location.href")
        check("camera-position=" in link, f"the address holds the frame's settings ({link})")
        driver.get(url + "?factor=3&view=factors")
        frame = driver.find_element(By.ID, "frame")
        linked = ready_with(lambda q: "factor=3" in q and "view=factors" in q)
        check(Select(driver.find_element(By.ID, "view")).first_selected_option.get_attribute("value") == "factors"
              and driver.find_element(By.ID, "factor").get_attribute("value") == "3",
              f"a link's settings are the page's: view and factor ({linked})")
        wait.until(lambda d: "--factor 3" in d.find_element(By.ID, "command").text)
        words = shlex.split(driver.find_element(By.ID, "command").text)
        expected = os.path.join(work, "linked.png")
        subprocess.run([binary] + words[1:-1] + [expected, "-q"], check=True)
        with open(expected, "rb") as f:
            check(f.read() == shown_bytes(), "the linked frame is the command's render of those settings")
        if screenshot:
            driver.save_screenshot(screenshot)
        print(f"first frame {first_query!r}, views {view_query!r}")
    finally:
        if driver is not None:
            driver.quit()
        server.send_signal(signal.SIGINT)
        try:
            code = server.wait(timeout=30)
        except subprocess.TimeoutExpired:
            server.kill()
            fail("the server did not stop within 30 s of SIGINT")
        shutil.rmtree(work, ignore_errors=True)
    check(code == 0, f"the server stops cleanly on SIGINT (exit {code})")


if __name__ == "__main__":
    main()
