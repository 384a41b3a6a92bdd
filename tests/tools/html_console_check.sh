#!/usr/bin/env bash
# html_console_check.sh FILE.html [more.html ...]
#
# Loads each page in headless Chromium and fails (exit 1), naming the page and printing the
# offending lines, when the page logs a console error or warning (console.error, console.warn,
# a failed console.assert, or a browser-side error/warning such as "Failed to load resource"),
# throws an uncaught exception, fails to load a resource (a missing <img>, script, stylesheet,
# an HTTP status >= 400), crashes, or does not finish loading within $HTML_CHECK_TIMEOUT seconds
# (default 60). console.log / console.info / console.debug are fine. Exit 0 when every page is
# clean; 77 (CTest's skip code) when Chromium ($CHROMIUM, default /usr/bin/chromium) or python3
# is missing; 2 for a bad command line.
#
# Why the DevTools protocol and not `chromium --enable-logging=stderr`: Chromium 156 writes every
# console message to stderr as "INFO:CONSOLE:<line>] "text", source: URL (line)" whatever its
# level (console.log and console.error look alike), and it does not log failed resource loads
# there at all. The DevTools protocol (over --remote-debugging-pipe: no port, no websocket
# library) reports each message with its level, every exception and every failed request.
# Chromium's own stderr (dbus, GPU, sandbox noise) goes to a file, shown only if it dies.
#
# HTML_CHECK_SETTLE (seconds, default 1) is how long a page keeps running after its load event,
# so that errors thrown by timers and animation frames are seen too.
set -u

if [[ $# -eq 0 ]]; then
  echo "usage: $0 FILE.html [more.html ...]" >&2
  exit 2
fi
source "$(dirname "$0")/chromium_or_skip.sh" html_console_check

profile=$(mktemp -d "${TMPDIR:-/tmp}/html_console_check.XXXXXX")
trap 'rm -rf "$profile"' EXIT

python3 - "$chromium" "$profile" "${HTML_CHECK_TIMEOUT:-60}" "${HTML_CHECK_SETTLE:-1}" "$@" <<'PY'
import fcntl, json, os, select, subprocess, sys, time

chromium, profile, timeout, settle = sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4])
pages = sys.argv[5:]


class BrowserGone(Exception):
    pass


class Browser:
    """Chromium with the DevTools protocol on fds 3 (commands in) and 4 (replies out), each
    message a JSON text ended by a NUL byte."""

    def __init__(self):
        cmd_r, self.cmd_w = os.pipe()
        self.out_r, out_w = os.pipe()
        # Move the child's ends above 9 first, so that dup2 onto 3 and 4 cannot clobber them.
        child_in = fcntl.fcntl(cmd_r, fcntl.F_DUPFD, 10)
        child_out = fcntl.fcntl(out_w, fcntl.F_DUPFD, 10)
        os.close(cmd_r)
        os.close(out_w)

        def wire():
            os.dup2(child_in, 3)
            os.dup2(child_out, 4)

        self.log_path = os.path.join(profile, "chromium-stderr.log")
        self.log = open(self.log_path, "wb")
        self.proc = subprocess.Popen(
            [chromium, "--headless", "--no-sandbox", "--disable-gpu", "--remote-debugging-pipe",
             "--user-data-dir=" + os.path.join(profile, "user-data"), "--no-first-run",
             "--no-default-browser-check", "--disable-extensions", "--disable-sync",
             "--disable-background-networking", "--disable-component-update", "--mute-audio",
             "about:blank"],
            stdin=subprocess.DEVNULL, stdout=self.log, stderr=self.log, preexec_fn=wire, pass_fds=(3, 4))
        os.close(child_in)
        os.close(child_out)
        self.buffer = b""
        self.next_id = 0
        self.events = []  # (sessionId, method, params), in arrival order

    def send(self, method, params=None, session=None):
        self.next_id += 1
        message = {"id": self.next_id, "method": method, "params": params or {}}
        if session:
            message["sessionId"] = session
        try:
            os.write(self.cmd_w, json.dumps(message).encode() + b"\0")
        except OSError as e:
            raise BrowserGone(f"cannot talk to Chromium: {e}")
        return self.next_id

    def pump(self, until):
        """Waits until something arrives or the time `until`; returns the replies read (id ->
        message) and files the events in self.events."""
        replies = {}
        left = until - time.monotonic()
        if left <= 0 or not select.select([self.out_r], [], [], left)[0]:
            return replies
        chunk = os.read(self.out_r, 1 << 20)
        if not chunk:
            raise BrowserGone("Chromium closed the DevTools pipe (it exited or crashed)")
        self.buffer += chunk
        *messages, self.buffer = self.buffer.split(b"\0")
        for raw in messages:
            m = json.loads(raw)
            if "id" in m:
                replies[m["id"]] = m
            else:
                self.events.append((m.get("sessionId"), m.get("method"), m.get("params", {})))
        return replies

    def call(self, method, params=None, session=None, deadline=None):
        ident = self.send(method, params, session)
        deadline = deadline or time.monotonic() + timeout
        while time.monotonic() < deadline:
            reply = self.pump(deadline).get(ident)
            if reply is not None:
                if "error" in reply:
                    raise BrowserGone(f"{method} failed: {reply['error'].get('message')}")
                return reply.get("result", {})
        raise TimeoutError(f"no reply to {method} within {timeout:g} s")

    def close(self):
        try:
            self.send("Browser.close")
            self.proc.wait(timeout=10)
        except (BrowserGone, subprocess.TimeoutExpired):
            self.proc.kill()
            self.proc.wait()
        self.log.close()

    def stderr_tail(self, lines=20):
        try:
            with open(self.log_path, "rb") as f:
                return b"\n".join(f.read().splitlines()[-lines:]).decode(errors="replace")
        except OSError:
            return ""


def where(url, line, column):
    url = url or "?"
    return f"{url}:{line + 1}:{column + 1}" if line is not None and line >= 0 else url


def text_of(args):
    parts = []
    for a in args:
        if "value" in a:
            parts.append(a["value"] if isinstance(a["value"], str) else json.dumps(a["value"]))
        else:
            parts.append(a.get("description") or a.get("unserializableValue") or a.get("type", "?"))
    return " ".join(str(p) for p in parts)


def problems_in(events, session):
    """The offending lines among the protocol events of one page."""
    out, requests = [], {}
    for sid, method, p in events:
        if sid != session:
            continue
        if method == "Runtime.consoleAPICalled" and p.get("type") in ("error", "warning", "assert"):
            frame = (p.get("stackTrace") or {}).get("callFrames") or [{}]
            out.append(f"console.{p['type']}: {text_of(p.get('args', []))} "
                       f"({where(frame[0].get('url'), frame[0].get('lineNumber'), frame[0].get('columnNumber'))})")
        elif method == "Runtime.exceptionThrown":
            d = p.get("exceptionDetails", {})
            desc = (d.get("exception") or {}).get("description") or d.get("text", "exception")
            out.append(f"uncaught exception: {desc.splitlines()[0]} "
                       f"({where(d.get('url'), d.get('lineNumber'), d.get('columnNumber'))})")
        elif method == "Log.entryAdded":
            e = p.get("entry", {})
            if e.get("level") in ("error", "warning"):
                out.append(f"browser {e['level']} ({e.get('source', '?')}): {e.get('text', '')}"
                           + (f" [{e['url']}]" if e.get("url") else ""))
        elif method == "Network.requestWillBeSent":
            requests[p.get("requestId")] = p.get("request", {}).get("url", "?")
        elif method == "Network.loadingFailed":
            url = requests.get(p.get("requestId"), "?")
            out.append(f"failed to load: {url} ({p.get('errorText', '?')}"
                       + (f", blocked: {p['blockedReason']}" if p.get("blockedReason") else "") + ")")
        elif method == "Network.responseReceived":
            r = p.get("response", {})
            status = r.get("status", 0)
            if isinstance(status, (int, float)) and status >= 400:
                out.append(f"failed to load: {r.get('url', '?')} (HTTP {status:g})")
        elif method in ("Inspector.targetCrashed", "Target.targetCrashed"):
            out.append("the page crashed")
    return out


def check(browser, path):
    """The offending lines for one page ([] when it is clean)."""
    if not os.path.isfile(path):
        return [f"no such file: {path}"]
    url = "file://" + os.path.abspath(path)
    target = browser.call("Target.createTarget", {"url": "about:blank"})["targetId"]
    session = browser.call("Target.attachToTarget", {"targetId": target, "flatten": True})["sessionId"]
    try:
        for domain in ("Runtime", "Log", "Network", "Page", "Inspector"):
            browser.call(domain + ".enable", session=session)
        start = len(browser.events)
        deadline = time.monotonic() + timeout
        nav = browser.call("Page.navigate", {"url": url}, session=session, deadline=deadline)
        if nav.get("errorText"):
            return [f"navigation failed: {nav['errorText']}"]
        loaded = lambda: any(s == session and m == "Page.loadEventFired" for s, m, _ in browser.events[start:])
        while not loaded() and time.monotonic() < deadline:
            browser.pump(deadline)
        found = []
        if not loaded():
            found.append(f"the page did not finish loading within {timeout:g} s")
        else:
            end = min(deadline, time.monotonic() + settle)
            while time.monotonic() < end:
                browser.pump(end)
        return problems_in(browser.events[start:], session) + found
    finally:
        try:
            browser.call("Target.closeTarget", {"targetId": target})
        except (BrowserGone, TimeoutError):
            pass


browser = Browser()
failed = 0
try:
    for page in pages:
        try:
            found = check(browser, page)
        except (BrowserGone, TimeoutError) as e:
            found = [str(e)]
            tail = browser.stderr_tail()
            if tail:
                found.append("Chromium's stderr ends with:\n    " + tail.replace("\n", "\n    "))
        if found:
            failed += 1
            print(f"html_console_check: {page}: FAIL")
            for line in found:
                print("  " + line)
        else:
            print(f"html_console_check: {page}: ok")
        if browser.proc.poll() is not None:
            browser = Browser()  # it died: a fresh one for the next page
finally:
    browser.close()
print(f"html_console_check: {len(pages) - failed}/{len(pages)} pages clean")
sys.exit(1 if failed else 0)
PY
