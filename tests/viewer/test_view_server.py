#!/usr/bin/python3
"""test_view_server.py LVSIM SOURCE_DIR - `lvsim view`'s server over HTTP (issue 22): it serves
its folder and nothing else, to the URL it prints and only to it.

A results folder from tests/missions/minimal.yaml, the viewer staged from a stand-in data
folder (stage.sh with a two-line CesiumJS: the test is about the server, not the page), then
raw HTTP requests on a socket (so the request line, the Host header and the bytes are exactly
the test's): the page and the CZML with the token; the token, a foreign or missing Host,
a listing, symlinks out of the folder, '..' and encoded tricks, a FIFO, other methods all
refused, without the refusal showing a file; and the folder unchanged by the server.
Exit 0 pass, 1 fail.
"""
import json
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time

LVSIM, SRC = sys.argv[1], sys.argv[2]
fails = 0
passes = 0


def check(ok, what, detail=''):
    global fails, passes
    if ok:
        passes += 1
    else:
        fails += 1
        print('FAIL: %s%s' % (what, '\n      ' + str(detail) if detail else ''))


def request(port, target, host='default', method='GET', extra=b'', version='HTTP/1.1'):
    """Sends one request as raw bytes; returns (status, headers dict lower-cased, body)."""
    if host == 'default':
        host = '127.0.0.1:%d' % port
    head = b'%s %s %s\r\n' % (method.encode(), target if isinstance(target, bytes)
                              else target.encode('latin-1'), version.encode())
    if host is not None:
        for h in host if isinstance(host, list) else [host]:
            head += b'Host: %s\r\n' % h.encode()
    head += b'Connection: close\r\n'
    if extra:
        head += b'Content-Length: %d\r\n' % len(extra)
    data = head + b'\r\n' + extra
    with socket.create_connection(('127.0.0.1', port), timeout=5) as s:
        s.sendall(data)
        got = b''
        while True:
            chunk = s.recv(65536)
            if not chunk:
                break
            got += chunk
    top, _, body = got.partition(b'\r\n\r\n')
    lines = top.decode('latin-1').split('\r\n')
    m = re.match(r'HTTP/1\.[01] (\d{3})', lines[0])
    status = int(m.group(1)) if m else 0
    headers = {}
    for line in lines[1:]:
        k, _, v = line.partition(':')
        headers[k.strip().lower()] = v.strip()
    return status, headers, body


def snapshot(root):
    """Every entry under root (symlinks not followed) with its type, size and mtime."""
    out = {}
    for d, dirs, files in os.walk(root):
        for n in dirs + files:
            p = os.path.join(d, n)
            st = os.lstat(p)
            out[os.path.relpath(p, root)] = (st.st_mode, st.st_size, st.st_mtime_ns)
    return out


def main():
    work = tempfile.mkdtemp(prefix='lvsim-view-test-')
    proc = None
    try:
        run = os.path.join(work, 'run')
        r = subprocess.run([LVSIM, 'run', os.path.join(SRC, 'tests/missions/minimal.yaml'),
                            '-o', run], capture_output=True, text=True)
        check(r.returncode == 0, 'lvsim run minimal.yaml', r.stderr)
        # the viewer staged from a stand-in data folder, as tests/cli/test_cli.sh does
        data = os.path.join(work, 'data', 'viewer')
        os.makedirs(data)
        shutil.copy(os.path.join(SRC, 'viewer', 'stage.sh'), data)
        shutil.copytree(os.path.join(SRC, 'viewer', 'web'), os.path.join(data, 'web'))
        for d in ('Assets', 'Workers', 'ThirdParty', 'Widgets'):
            os.makedirs(os.path.join(data, 'cesium', d))
        with open(os.path.join(data, 'cesium', 'Cesium.js'), 'w') as f:
            f.write('// stand-in\n')
        with open(os.path.join(data, 'cesium', 'package.json'), 'w') as f:
            f.write('{"name": "cesium", "version": "0.0.7"}\n')
        env = dict(os.environ, LVSIM_DATA=os.path.join(work, 'data'))
        r = subprocess.run([LVSIM, 'view', run, '--stage-only'], env=env, capture_output=True,
                           text=True)
        check(r.returncode == 0, 'lvsim view --stage-only', r.stderr)

        # what the server must never give: a file outside the folder, reached by symlinks
        secret = 'lvsim-view-test-secret-%d' % os.getpid()
        outside = os.path.join(work, 'outside')
        os.makedirs(outside)
        with open(os.path.join(outside, 'secret.txt'), 'w') as f:
            f.write(secret + '\n')
        with open(os.path.join(outside, 'index.html'), 'w') as f:
            f.write(secret + '\n')
        os.symlink(os.path.join(outside, 'secret.txt'), os.path.join(run, 'leak.txt'))
        os.symlink('../outside/secret.txt', os.path.join(run, 'leak_rel.txt'))
        os.symlink(outside, os.path.join(run, 'leakdir'))
        os.symlink('/etc/hostname', os.path.join(run, 'hostname'))
        os.makedirs(os.path.join(run, 'sub'))
        os.symlink(os.path.join(outside, 'index.html'), os.path.join(run, 'sub', 'index.html'))
        os.symlink('summary.json', os.path.join(run, 'alias.json'))  # inside: served
        os.mkfifo(os.path.join(run, 'fifo'))
        before = snapshot(run)

        proc = subprocess.Popen([LVSIM, 'view', run], env=env, stdout=subprocess.PIPE,
                                stderr=subprocess.STDOUT, text=True)
        line = ''
        t0 = time.time()
        while time.time() - t0 < 20:
            line = proc.stdout.readline()
            if line.startswith('lvsim view: http') or line == '':
                break
        m = re.match(r'lvsim view: http://127\.0\.0\.1:(\d+)/([^/ ]+)/viewer/ ', line)
        check(m is not None, 'lvsim view prints http://127.0.0.1:PORT/TOKEN/viewer/', line)
        if m is None:
            return
        port, token = int(m.group(1)), m.group(2)
        check(re.fullmatch(r'[0-9a-f]{32}', token) is not None, 'the token has 128 bits (hex)',
              token)
        with open('/proc/%d/cmdline' % proc.pid, 'rb') as f:
            check(token.encode() not in f.read(), 'the token is not on the command line')
        t = '/' + token
        for _ in range(100):  # the server is up once python3 has started
            try:
                request(port, t + '/summary.json')
                break
            except OSError:
                time.sleep(0.05)

        def body_of(name):
            with open(os.path.join(run, name), 'rb') as f:
                return f.read()

        # the page, the CZML, the summary: served with the token
        st, h, b = request(port, t + '/viewer/')
        check(st == 200 and b == body_of('viewer/index.html'), 'GET TOKEN/viewer/ is the page',
              st)
        st, h, b = request(port, t + '/viewer/app.js')
        check(st == 200 and b == body_of('viewer/app.js'), 'GET TOKEN/viewer/app.js', st)
        st, h, b = request(port, t + '/mission.czml')
        check(st == 200 and b == body_of('mission.czml') and isinstance(json.loads(b), list),
              'GET TOKEN/mission.czml is the CZML document', st)
        st, h, b = request(port, t + '/summary.json', host='localhost:%d' % port)
        check(st == 200 and b == body_of('summary.json'), 'Host localhost:PORT is served', st)
        st, h, b = request(port, t + '/viewer/index.html?czml=../mission.czml')
        check(st == 200 and b == body_of('viewer/index.html'), 'a query string is ignored', st)
        st, h, b = request(port, t + '/alias.json')
        check(st == 200 and b == body_of('summary.json'),
              'a symlink to a file inside the folder is served', st)
        st, h, b = request(port, t + '/summary.json', method='HEAD')
        check(st == 200 and b == b'' and h.get('content-length') == str(len(body_of(
            'summary.json'))), 'HEAD: the length, no body', (st, h, b[:80]))
        st, h, b = request(port, t + '/viewer')
        check(st == 301 and h.get('location') == t + '/viewer/',
              'a folder without its slash: redirect keeping the token', (st, h))
        st, h, b = request(port, t + '/')
        check(st == 200 and b == body_of('index.html'), 'the folder with index.html: the report',
              st)
        st, h, b = request(port, t + '/%73ummary.json')
        check(st == 200 and b == body_of('summary.json'), 'percent-encoded name decoded', st)

        # every refusal: none gives a file's bytes or names one
        names = [n for n in os.listdir(run)] + os.listdir(os.path.join(run, 'plots'))

        def refused(target, codes, what, **kw):
            try:
                st, h, b = request(port, target, **kw)
            except OSError as e:
                check(False, what, 'no answer: %s' % e)
                return
            text = b.decode('latin-1')
            leak = [n for n in names if n in text] + ([secret] if secret in text else [])
            check(st in codes and not leak, what, 'status %d, body %r' % (st, b[:200]))

        dns = {403, 421}
        refused(t + '/summary.json', dns, 'foreign Host header refused',
                host='evil.example:%d' % port)
        refused(t + '/summary.json', dns, 'Host 127.0.0.1 on another port refused',
                host='127.0.0.1:%d' % (port + 1 if port < 65535 else port - 1))
        refused(t + '/summary.json', dns, 'Host 127.0.0.1.evil.example refused',
                host='127.0.0.1.evil.example:%d' % port)
        refused(t + '/summary.json', dns, 'missing Host header refused (HTTP/1.0)', host=None,
                version='HTTP/1.0')
        refused(t + '/summary.json', dns, 'missing Host header refused (HTTP/1.1)', host=None)
        refused(t + '/summary.json', dns | {400}, 'two Host headers refused',
                host=['127.0.0.1:%d' % port, 'evil.example:%d' % port])
        for target in ('/', '/summary.json', '/viewer/', '/mission.czml', '/plots/',
                       '/%s/summary.json' % ('0' * 32), t.upper() + '/summary.json',
                       t[:-1] + '/summary.json', t + 'x/summary.json', '/x' + t + '/summary.json',
                       'http://127.0.0.1:%d%s/summary.json' % (port, t), '*'):
            refused(target, {403}, 'no token: %s refused' % target[:60])
        refused(t + '/plots/', {404}, 'no listing: TOKEN/plots/ (no index.html) is 404')
        refused(t + '/viewer/cesium/', {404}, 'no listing: TOKEN/viewer/cesium/ is 404')
        refused(t + '/leak.txt', {403, 404}, 'symlink to a file outside refused')
        refused(t + '/leak_rel.txt', {403, 404}, 'relative symlink ../outside refused')
        refused(t + '/leakdir/secret.txt', {403, 404}, 'symlinked folder outside refused')
        refused(t + '/leakdir/', {403, 404}, 'symlinked folder outside: no index, no listing')
        refused(t + '/hostname', {403, 404}, 'symlink to /etc/hostname refused')
        refused(t + '/sub/', {403, 404}, 'a folder whose index.html leads outside refused')
        refused(t + '/fifo', {403, 404}, 'a FIFO refused (and no hang)')
        refused(t + '/nothing.json', {404}, 'a missing file: 404')
        for target in ('/../outside/secret.txt', '/%2e%2e/outside/secret.txt',
                       '/..%2foutside%2fsecret.txt', '/viewer/../../outside/secret.txt',
                       '/viewer/%2e%2e/%2e%2e/outside/secret.txt', '//etc/hostname',
                       '/%2fetc%2fhostname', '/./summary.json', '/summary.json%00.png',
                       '/summary.json%00', '/viewer//index.html', '/' + outside + '/secret.txt'):
            refused(t + target, {400, 403, 404}, 'path trick %s refused' % target)
        refused(t.encode() + b'/summary.json\x00', {400, 403, 404}, 'a raw NUL refused')
        for method in ('POST', 'PUT', 'DELETE', 'PATCH', 'OPTIONS'):
            refused(t + '/summary.json', {405, 501}, '%s refused' % method, method=method,
                    extra=b'{"x": 1}')
        refused(t + '/new.txt', {405, 501}, 'PUT of a new file refused', method='PUT',
                extra=b'written')
        check(proc.poll() is None, 'the server is still running after the bad requests')
        check(snapshot(run) == before, 'the server wrote nothing into the folder',
              set(snapshot(run).items()) ^ set(before.items()))
    finally:
        if proc is not None:
            proc.send_signal(signal.SIGINT)
            try:
                out, _ = proc.communicate(timeout=10)
                check('Traceback' not in out, 'no traceback at Ctrl-C', out)
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.communicate()
                check(False, 'lvsim view ends at SIGINT')
        shutil.rmtree(work, ignore_errors=True)
    print('test_view_server: %d passed, %d failed' % (passes, fails))


main()
sys.exit(1 if fails else 0)
