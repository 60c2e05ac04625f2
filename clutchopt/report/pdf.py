"""The review page as PDF, printed by headless Chromium (``--print-to-pdf``): the page's own print stylesheet
(A4, tables that fit the width) laid out by a real browser engine, the same one the tests look at the page with."""

from __future__ import annotations

import os
import shutil
import subprocess
import tempfile
from pathlib import Path

from clutchopt.errors import InputError

CHROMIUM = ("chromium", "chromium-browser", "google-chrome", "chrome")
INSTALL = "install Chromium (Debian and Ubuntu: apt-get install chromium) or write .html"
TIMEOUT_S = 120.0


def find_chromium() -> str | None:
    return next((path for path in map(shutil.which, CHROMIUM) if path), None)


def require_chromium(option: str) -> str:
    """The Chromium to print with; an InputError naming ``option`` and what to install where there is none."""
    binary = find_chromium()
    if binary is None:
        raise InputError(option, f"writing a PDF needs headless Chromium, and none is on the PATH: {INSTALL}")
    return binary


def print_pdf(binary: str, html: str, path: str, option: str) -> None:
    """Print the page ``html`` to the PDF file ``path`` with Chromium ``binary``; its failures are InputErrors."""
    with tempfile.TemporaryDirectory() as folder:
        page = Path(folder) / "review.html"
        page.write_text(html, encoding="utf-8")
        command = [binary, "--headless", "--disable-gpu", "--no-first-run", "--no-pdf-header-footer",
                   f"--user-data-dir={folder}/profile", f"--print-to-pdf={os.path.abspath(path)}", page.as_uri()]
        if os.geteuid() == 0:
            command.insert(1, "--no-sandbox")  # Chromium will not start its sandbox as root
        try:
            done = subprocess.run(command, stdin=subprocess.DEVNULL, capture_output=True, text=True,
                                  timeout=TIMEOUT_S)
        except subprocess.TimeoutExpired:
            raise InputError(option, f"Chromium did not print the page within {TIMEOUT_S:g} s") from None
    if done.returncode != 0 or not os.path.getsize(path):
        said = (done.stderr.strip().splitlines() or ["no message"])[-1]
        raise InputError(option, f"Chromium could not print the page (exit code {done.returncode}): {said}")
