#!/usr/bin/env python3
"""Drives the control page in headless Chromium over the DevTools protocol, as an operator would use it:
    control_page_driver.py CHROMIUM URL PARAM POSITION [SCREENSHOT.png]
opens URL, waits until the page has read the namespace and opened its WebSocket (body data-ready = 1), counts
its sliders, moves PARAM's slider to POSITION (0..1000, as a finger would: an input event) and presses the burst
button; with SCREENSHOT, first saves the page as a phone shows it (390 x 844 CSS pixels). Prints one line per finding
("sliders 58", "load_ms 123.4", "console_errors 0", "slider PARAM VALUE" with the value the slider set, "clicked burst"), then the console
errors themselves; exits 1 when the page never became ready. Bounded: 60 s in all."""
import base64
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
import urllib.request

import websocket  # python3-websocket (Debian)


class DevTools:
    def __init__(self, url):
        self.ws = websocket.create_connection(url, timeout=30)
        self.next_id = 0
        self.events = []

    def call(self, method, **params):
        self.next_id += 1
        self.ws.send(json.dumps({"id": self.next_id, "method": method, "params": params}))
        while True:
            message = json.loads(self.ws.recv())
            if message.get("id") == self.next_id:
                if "error" in message:
                    raise RuntimeError(f"{method}: {message['error']}")
                return message.get("result", {})
            self.events.append(message)

    def evaluate(self, expression):
        result = self.call("Runtime.evaluate", expression=expression, returnByValue=True, awaitPromise=True)
        return result.get("result", {}).get("value")


def errors_of(events):
    found = []
    for e in events:
        method, params = e.get("method"), e.get("params", {})
        if method == "Runtime.exceptionThrown":
            found.append("exception: " + params["exceptionDetails"].get("text", "") + " " +
                         str(params["exceptionDetails"].get("exception", {}).get("description", "")))
        elif method == "Runtime.consoleAPICalled" and params.get("type") in ("error", "assert"):
            found.append("console: " + " ".join(str(a.get("value", a.get("description", ""))) for a in params["args"]))
        elif method == "Log.entryAdded" and params["entry"].get("level") == "error":
            found.append("log: " + params["entry"].get("text", "") + " " + params["entry"].get("url", ""))
    return found


def main():
    chromium, url, param, position = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
    profile = tempfile.mkdtemp(prefix="gb_chromium_")
    browser = subprocess.Popen([chromium, "--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
                                "--remote-debugging-port=0", "--user-data-dir=" + profile, "about:blank"],
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        port_file = os.path.join(profile, "DevToolsActivePort")
        deadline = time.time() + 30
        while not os.path.exists(port_file) and time.time() < deadline:
            time.sleep(0.1)
        port = open(port_file).read().split()[0]
        targets = json.load(urllib.request.urlopen(f"http://127.0.0.1:{port}/json/list"))
        page = next(t for t in targets if t["type"] == "page")
        tools = DevTools(page["webSocketDebuggerUrl"])
        for domain in ("Runtime", "Log", "Page"):
            tools.call(domain + ".enable")
        started = time.time()
        tools.call("Page.navigate", url=url)
        ready = False
        while time.time() - started < 30:
            if tools.evaluate("document.body && document.body.dataset.ready") == "1":
                ready = True
                break
            time.sleep(0.05)
        print(f"load_ms {1000 * (time.time() - started):.1f}")
        if not ready:
            print("page never ready: " + str(tools.evaluate("document.body && document.body.innerText")))
            return 1
        if len(sys.argv) > 5:
            tools.call("Emulation.setDeviceMetricsOverride", width=390, height=844, deviceScaleFactor=2, mobile=True)
            tools.evaluate("document.querySelector('details').open = true")
            time.sleep(1.5)  # a status line from the show
            shot = tools.call("Page.captureScreenshot", format="png")
            with open(sys.argv[5], "wb") as f:
                f.write(base64.b64decode(shot["data"]))
        print("sliders", tools.evaluate("document.querySelectorAll('input[type=range]').length"))
        print("groups", tools.evaluate("document.querySelectorAll('details').length"))
        print("cues", tools.evaluate("document.querySelectorAll('#cues button').length"))
        moved = tools.evaluate(f"""(() => {{
            const slider = document.querySelector('input[type=range][name="{param}"]');
            const number = document.querySelector('input[name="{param}_value"]');
            if (!slider) return null;
            slider.value = {position};
            slider.dispatchEvent(new Event('input', {{bubbles: true}}));
            return number.value; }})()""")
        print("slider", param, moved)
        time.sleep(1.0)
        clicked = tools.evaluate("(() => { const b = document.getElementById('cue-burst'); if (!b) return false; "
                                 "b.click(); return true; })()")
        print("clicked burst" if clicked else "no burst button")
        time.sleep(2.0)  # the status the show sends back, over LISTEN
        print("status", tools.evaluate("document.getElementById('status').textContent"))
        tools.call("Runtime.evaluate", expression="1")  # collects the events that came meanwhile
        errors = errors_of(tools.events)
        print("console_errors", len(errors))
        for e in errors:
            print("  " + e)
        return 0
    finally:
        browser.terminate()
        try:
            browser.wait(10)
        except subprocess.TimeoutExpired:
            browser.kill()
        shutil.rmtree(profile, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
