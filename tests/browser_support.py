"""What the browser tests share: their verdict lines, and headless Chromium driven by Selenium, or exit 77
(ctest: skipped) with the reason when Chromium, ChromeDriver or Selenium is absent."""
import os
import sys

CHROMIUM = "/usr/bin/chromium"
CHROMEDRIVER = "/usr/bin/chromedriver"


def skip(reason):
    print(f"SKIPPED: {reason}")
    sys.exit(77)


def fail(message):
    print(f"FAILED: {message}")
    sys.exit(1)


def check(condition, message):
    if not condition:
        fail(message)
    print(f"ok: {message}")


def require_browser():
    """Skips the test (exit 77) unless Chromium, ChromeDriver and Selenium are installed."""
    for path, what in ((CHROMIUM, "chromium"), (CHROMEDRIVER, "chromium-driver")):
        if not os.path.exists(path):
            skip(f"{path} is absent (Debian package {what}; scripts/setup.sh installs it)")
    try:
        import selenium  # noqa: F401
    except ImportError:
        skip("python3-selenium is absent (scripts/setup.sh installs it)")


def headless_chromium(profile_dir, *extra_flags):
    """A headless Chromium at 1280x900 with its profile in `profile_dir`; the caller quits it."""
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service
    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for flag in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                 "--window-size=1280,900", f"--user-data-dir={profile_dir}") + extra_flags:
        options.add_argument(flag)
    return webdriver.Chrome(service=Service(CHROMEDRIVER), options=options)
