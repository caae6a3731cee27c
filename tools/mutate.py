#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""mutate.py - measure the tests by mutation: put small, plausible bugs
(tests/mutants.txt) into the core one at a time, rebuild, run the tests
that touch the changed code, and count the bugs they catch.

    python3 tools/mutate.py [--mutants tests/mutants.txt] [--only PAT[,PAT]]
                            [--pending] [--equivalent] [--full] [--min PCT]
                            [--workdir DIR] [--jobs N] [--list]

Nothing is changed in the working tree.  The tracked and untracked (not
ignored) files are copied into a scratch tree (a temporary directory, or
--workdir DIR, kept between runs so the next run rebuilds only what changed),
built once unmutated, and every mutant is applied there, built, tested and
reverted.

Which tests run for a mutant (chosen per number type):
  * the core objects whose bytes differ from the unmutated build (so a
    mutant inside `#if TG_FIXED` runs only the fixed tests, a mutant in a
    header every object it reaches; no object changed at all = equivalent
    by construction, reported and not counted);
  * every test program that links one of those objects (a test program
    holds a static-library member only when it uses it: `nm` of the
    programs against the objects' global symbols, once, on the unmutated
    build);
  * the golden test (tests/golden_test.sh, every built-in scene in both
    number types through the CLI) always.
The test programs naming one of the changed objects' functions in their
source run first, the rest after, each group fastest first (times from the
unmutated run); the first failure, crash or time-out (10 x its unmutated
time, at least 60 s) catches the mutant and the rest are skipped (--full
runs them all and lists every test that catches it).

tests/mutants.txt holds one record per mutant:

    [id]
    file: src/light/sh.c
    find: #define SH_Y1  TG_R(0.488602512f)
    replace: #define SH_Y1  TG_R(0.487602512f)
    what: an SH9 band-1 basis constant wrong in the third digit

`find` must occur exactly once in `file`; `\\n` in find/replace is a
newline, `\\\\` a backslash.  Optional lines: `equivalent: REASON` (a
mutant that changes nothing observable: not run unless --equivalent, not
counted), and the comment `# pending: REASON` inside a record (its area is
being rewritten: run only with --pending, reported apart).  Lines starting
with `#` are comments.

Output: one line per mutant (caught by which test, or MISSED), then the
caught percentage per area (the source directory and file) and overall.
Exit status 0; 1 when --min PCT is given and fewer are caught; 2 for a bad
mutant file (a snippet not found or not unique) or an unmutated tree whose
tests fail.
"""
import argparse
import fnmatch
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
NUMS = ('float', 'fixed')
GOLDEN = 'tests/golden_test.sh'
TIMEOUT_FACTOR, TIMEOUT_MIN = 10, 60.0
MARKER = 'mutate-applied'   # in the scratch tree while a mutant is in place


class Mutant:
    def __init__(self, ident, line):
        self.id, self.line = ident, line
        self.file = self.find = self.replace = self.what = None
        self.equivalent = None
        self.pending = None


def unescape(s):
    out, i = [], 0
    while i < len(s):
        if s[i] == '\\' and i + 1 < len(s) and s[i + 1] in 'n\\':
            out.append('\n' if s[i + 1] == 'n' else '\\')
            i += 2
        else:
            out.append(s[i])
            i += 1
    return ''.join(out)


def parse_mutants(path):
    mutants, cur, errors = [], None, []
    keys = {'file', 'find', 'replace', 'what', 'equivalent'}
    with open(path, encoding='utf-8') as f:
        for n, raw in enumerate(f, 1):
            line = raw.rstrip('\n')
            m = re.match(r'^\[([A-Za-z0-9_.-]+)\]\s*$', line)
            if m:
                cur = Mutant(m.group(1), n)
                mutants.append(cur)
                continue
            pm = re.match(r'^#\s*pending:\s*(.*)$', line)
            if pm and cur is not None:
                cur.pending = pm.group(1).strip() or 'pending'
                continue
            if not line.strip() or line.lstrip().startswith('#'):
                continue
            km = re.match(r'^([a-z]+):(?: (.*))?$', line)
            if not km or km.group(1) not in keys or cur is None:
                errors.append('%s:%d: error: expected "[id]" or one of %s: ...' % (path, n, ', '.join(sorted(keys))))
                continue
            value = km.group(2) or ''
            setattr(cur, km.group(1), unescape(value) if km.group(1) in ('find', 'replace') else value.strip())
    seen = set()
    for m in mutants:
        where = '%s:%d' % (path, m.line)
        if m.id in seen:
            errors.append('%s: error: mutant id %s used twice' % (where, m.id))
        seen.add(m.id)
        for k in ('file', 'find', 'replace', 'what'):
            if getattr(m, k) is None:
                errors.append('%s: error: mutant %s has no "%s:"' % (where, m.id, k))
        if m.find is not None and m.find == m.replace:
            errors.append('%s: error: mutant %s replaces its snippet with itself' % (where, m.id))
    return mutants, errors


def check_snippets(mutants, tree, path):
    errors = []
    for m in mutants:
        p = os.path.join(tree, m.file)
        if not os.path.isfile(p):
            errors.append('%s:%d: error: mutant %s: no file %s' % (path, m.line, m.id, m.file))
            continue
        with open(p, encoding='utf-8') as f:
            count = f.read().count(m.find)
        if count != 1:
            errors.append('%s:%d: error: mutant %s: the snippet occurs %d times in %s (must be once)'
                          % (path, m.line, m.id, count, m.file))
    return errors


# ---- the scratch tree ----

def project_files():
    out = subprocess.run(['git', 'ls-files', '-z', '--cached', '--others', '--exclude-standard'],
                         cwd=ROOT, check=True, capture_output=True).stdout.decode()
    return [f for f in out.split('\0') if f and os.path.isfile(os.path.join(ROOT, f))]


def sync_tree(work):
    """Copy the project into work; unchanged files keep their time stamps
    (so make rebuilds only what changed), files gone from the project go.
    A file a killed run left mutated (MARKER names it) is rebuilt."""
    files = set(project_files())
    marker = os.path.join(work, MARKER)
    if os.path.isfile(marker):
        with open(marker, encoding='utf-8') as f:
            left = os.path.join(work, f.read().strip())
        if os.path.isfile(left):
            os.remove(left)       # copied afresh below, with a new time stamp
        os.remove(marker)
    for rel in sorted(files):
        src, dst = os.path.join(ROOT, rel), os.path.join(work, rel)
        with open(src, 'rb') as f:
            data = f.read()
        if os.path.isfile(dst):
            with open(dst, 'rb') as f:
                if f.read() == data:
                    continue
        os.makedirs(os.path.dirname(dst), exist_ok=True)
        shutil.copyfile(src, dst)      # a fresh time stamp: make rebuilds what depends on it
        shutil.copymode(src, dst)
    for top in ('src', 'tests', 'tools', 'platform', 'examples'):
        for dirpath, _, names in os.walk(os.path.join(work, top)):
            for name in names:
                rel = os.path.relpath(os.path.join(dirpath, name), work)
                if rel not in files:
                    os.remove(os.path.join(work, rel))


def make(work, targets, jobs, log):
    cmd = ['make', '--no-print-directory', '-j%d' % jobs, 'BUILD=build', 'DEV=', 'WERROR='] + targets
    r = subprocess.run(cmd, cwd=work, stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    with open(log, 'wb') as f:
        f.write(r.stdout)
    return r.returncode == 0


def core_objects(work, num):
    base = os.path.join(work, 'build', num, 'core')
    objs = {}
    for dirpath, _, names in os.walk(base):
        for name in names:
            if name.endswith('.o'):
                p = os.path.join(dirpath, name)
                with open(p, 'rb') as f:
                    objs[os.path.relpath(p, base)] = f.read()
    return objs


def nm_globals(path, defined):
    args = ['nm', '-g', '--defined-only' if defined else '--undefined-only', path]
    out = subprocess.run(args, capture_output=True, text=True).stdout
    syms = set()
    for line in out.splitlines():
        parts = line.split()
        if len(parts) >= 2:
            syms.add(parts[-1])
    return syms


def test_names(work):
    return sorted(os.path.splitext(f)[0] for f in os.listdir(os.path.join(work, 'tests'))
                  if re.match(r'^test_.*\.c$', f))


def link_map(work, num, objs, tests):
    """object -> test programs that hold it; object -> its global symbols."""
    symbols = {o: nm_globals(os.path.join(work, 'build', num, 'core', o), True) for o in objs}
    holders = {o: set() for o in objs}
    for t in tests:
        have = nm_globals(os.path.join(work, 'build', num, 'tests', t), True)
        for o, syms in symbols.items():
            if syms & have:
                holders[o].add(t)
    return holders, symbols


def plain_name(sym):
    return re.sub(r'_(f32|q16)$', '', sym)


# ---- running tests ----

def run_test(work, num, test, timeout):
    """(passed, detail)."""
    if test == GOLDEN:
        cmd, env = ['bash', GOLDEN], dict(os.environ, BUILD='build')
    else:
        cmd, env = [os.path.join('build', num, 'tests', test)], dict(os.environ)
    try:
        r = subprocess.run(cmd, cwd=work, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                           timeout=timeout)
    except subprocess.TimeoutExpired:
        return False, 'timed out after %.0f s' % timeout
    out = r.stdout.decode(errors='replace')
    if r.returncode == 0 and re.search(r'^TESTS passed \d+ failed 0$', out, re.M):
        return True, ''
    fails = [l for l in out.splitlines() if l.startswith('FAIL')]
    if r.returncode < 0:
        return False, 'crashed (signal %d)' % -r.returncode
    if not re.search(r'^TESTS passed', out, re.M):
        return False, 'exited early (status %d)' % r.returncode
    return False, fails[0] if fails else 'status %d' % r.returncode


def label(num, test):
    return 'golden' if test == GOLDEN else '%s/%s' % (num, test)


class Suite:
    """The unmutated build: objects, link maps, test times."""

    def __init__(self, work, jobs, logdir):
        self.work, self.jobs, self.logdir = work, jobs, logdir
        self.tests = test_names(work)
        self.objs, self.holders, self.symbols, self.times = {}, {}, {}, {}
        self.sources = {}
        for t in self.tests:
            with open(os.path.join(work, 'tests', t + '.c'), encoding='utf-8', errors='replace') as f:
                self.sources[t] = f.read()

    def build_all(self):
        targets = ['build/libtinygi.a', 'build/libtinygi-fixed.a', 'build/tinygi', 'build/tinygi-fixed']
        targets += ['build/%s/tests/%s' % (n, t) for n in NUMS for t in self.tests]
        return make(self.work, targets, self.jobs, os.path.join(self.logdir, 'build-unmutated.log'))

    def measure(self):
        for num in NUMS:
            self.objs[num] = core_objects(self.work, num)
            self.holders[num], self.symbols[num] = link_map(self.work, num, self.objs[num], self.tests)
        bad = []
        for num in NUMS:
            for t in self.tests:
                start = time.time()
                ok, detail = run_test(self.work, num, t, None)
                self.times[(num, t)] = time.time() - start
                if not ok:
                    bad.append('%s: %s' % (label(num, t), detail))
        start = time.time()
        ok, detail = run_test(self.work, None, GOLDEN, None)
        self.times[(None, GOLDEN)] = time.time() - start
        if not ok:
            bad.append('golden: %s' % detail)
        return bad

    def plan(self, changed):
        """Ordered (num, test) runs for the changed objects {num: [obj]}."""
        runs = []
        for num in NUMS:
            objs = changed.get(num, [])
            if not objs:
                continue
            names = set()
            for o in objs:
                names |= {plain_name(s) for s in self.symbols[num].get(o, ())}
            holders = set()
            for o in objs:
                holders |= self.holders[num].get(o, set())
            for t in holders:
                src = self.sources[t]
                direct = any(re.search(r'\b%s\b' % re.escape(s), src) for s in names)
                runs.append((0 if direct else 1, self.times[(num, t)], num, t))
        runs.sort()
        out = [(num, t) for _, _, num, t in runs]
        # the golden test after the directly-naming programs
        k = sum(1 for r in runs if r[0] == 0)
        return out[:k] + [(None, GOLDEN)] + out[k:]

    def timeout(self, num, test):
        return max(TIMEOUT_MIN, TIMEOUT_FACTOR * self.times[(num, test)])


def run_mutant(suite, m, full):
    """('caught'|'missed'|'equivalent-object'|'no-build', [catchers], note)."""
    work = suite.work
    path = os.path.join(work, m.file)
    with open(path, encoding='utf-8') as f:
        original = f.read()
    mutated = original.replace(m.find, m.replace, 1)
    marker = os.path.join(work, MARKER)
    try:
        with open(marker, 'w', encoding='utf-8') as f:
            f.write(m.file)
        with open(path, 'w', encoding='utf-8') as f:
            f.write(mutated)
        log = os.path.join(suite.logdir, 'build-%s.log' % m.id)
        if not make(work, ['build/libtinygi.a', 'build/libtinygi-fixed.a'], suite.jobs, log):
            return 'no-build', [], 'see %s' % log
        changed = {}
        for num in NUMS:
            now = core_objects(work, num)
            changed[num] = sorted(o for o in now if now[o] != suite.objs[num].get(o))
        if not changed['float'] and not changed['fixed']:
            return 'equivalent-object', [], 'no object changed'
        runs = suite.plan(changed)
        catchers, notes = [], []
        for num, t in runs:
            # each program linked just before it runs: a mutant caught by
            # the first test costs one link, not one per program
            target = ['build/tinygi', 'build/tinygi-fixed'] if t == GOLDEN else ['build/%s/tests/%s' % (num, t)]
            if not make(work, target, suite.jobs, log):
                return 'no-build', [], 'see %s' % log
            ok, detail = run_test(work, num, t, suite.timeout(num, t))
            if not ok:
                catchers.append(label(num, t))
                notes.append(detail)
                if not full:
                    break
        which = '+'.join(n for n in NUMS if changed[n])
        if catchers:
            return 'caught', catchers, notes[0]
        return 'missed', [], '%d runs, %s objects changed: %s' % (
            len(runs), which, ', '.join(sorted(set(changed['float']) | set(changed['fixed']))))
    finally:
        with open(path, 'w', encoding='utf-8') as f:
            f.write(original)
        os.remove(marker)


def area_of(path):
    return path[4:] if path.startswith('src/') else path


def summarise(results, out):
    counted = [(m, r) for m, r in results if r[0] in ('caught', 'missed') and not m.pending]
    pend = [(m, r) for m, r in results if r[0] in ('caught', 'missed') and m.pending]

    def table(rows, title):
        if not rows:
            return
        out('')
        out(title)
        by = {}
        for m, r in rows:
            for key in (os.path.dirname(area_of(m.file)) + '/', area_of(m.file)):
                c = by.setdefault(key, [0, 0])
                c[1] += 1
                c[0] += r[0] == 'caught'
        for key in sorted(by, key=lambda k: (k.split('/')[0], not k.endswith('/'), k)):
            c, n = by[key]
            indent = '  ' if key.endswith('/') else '    '
            out('%s%-28s %3d / %-3d %5.1f%%' % (indent, key, c, n, 100.0 * c / n))
        caught = sum(1 for _, r in rows if r[0] == 'caught')
        out('  %-28s %3d / %-3d %5.1f%%' % ('all', caught, len(rows), 100.0 * caught / len(rows)))
        missed = [(m, r) for m, r in rows if r[0] == 'missed']
        if missed:
            out('  missed:')
            for m, r in missed:
                out('    %-32s %s: %s' % (m.id, m.file, m.what))

    table(counted, 'caught per area (stable areas):')
    table(pend, 'caught per area (pending: areas being rewritten):')
    other = [(m, r) for m, r in results if r[0] not in ('caught', 'missed')]
    if other:
        out('')
        out('not counted:')
        for m, r in other:
            out('  %-32s %-18s %s' % (m.id, r[0], r[2] or m.equivalent or ''))
    if not counted:
        return None
    return 100.0 * sum(1 for _, r in counted if r[0] == 'caught') / len(counted)


def main():
    # SIGTERM and SIGHUP unwind like ^C, so a stopped run reverts its mutant
    for sig in (signal.SIGTERM, signal.SIGHUP):
        signal.signal(sig, lambda *_: sys.exit(130))
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('--mutants', default=os.path.join(ROOT, 'tests', 'mutants.txt'))
    ap.add_argument('--only', help='comma-separated id patterns (fnmatch), or file paths')
    ap.add_argument('--pending', action='store_true', help='also run the pending mutants')
    ap.add_argument('--equivalent', action='store_true', help='also run the ones marked equivalent')
    ap.add_argument('--full', action='store_true', help='run every selected test, list all that catch')
    ap.add_argument('--min', type=float, help='exit 1 when fewer than PCT percent are caught')
    ap.add_argument('--workdir', help='scratch tree kept between runs (default: a temporary one)')
    ap.add_argument('--jobs', type=int, default=2, help='make -j (default 2)')
    ap.add_argument('--list', action='store_true', help='list the mutants and exit')
    args = ap.parse_args()

    mutants, errors = parse_mutants(args.mutants)
    errors += check_snippets(mutants, ROOT, args.mutants)
    if errors:
        print('\n'.join(errors), file=sys.stderr)
        return 2
    chosen = []
    for m in mutants:
        if args.only:
            pats = args.only.split(',')
            if not any(fnmatch.fnmatch(m.id, p) or m.file == p or m.file.startswith(p.rstrip('/') + '/')
                       for p in pats):
                continue
        elif m.pending and not args.pending:
            continue
        chosen.append(m)
    if args.list:
        for m in chosen:
            tag = ' [pending]' if m.pending else ' [equivalent]' if m.equivalent else ''
            print('%-32s %-28s %s%s' % (m.id, m.file, m.what, tag))
        return 0

    started = time.time()
    tmp = None
    if args.workdir:
        work = os.path.abspath(args.workdir)
        os.makedirs(work, exist_ok=True)
    else:
        tmp = tempfile.mkdtemp(prefix='tinygi-mutate-')
        work = tmp
    logdir = os.path.join(work, 'mutate-logs')
    os.makedirs(logdir, exist_ok=True)
    try:
        print('mutate: scratch tree %s' % work, flush=True)
        sync_tree(work)
        suite = Suite(work, args.jobs, logdir)
        if not suite.build_all():
            print('mutate: the unmutated tree does not build (%s)' % os.path.join(logdir, 'build-unmutated.log'))
            return 2
        bad = suite.measure()
        if bad:
            print('mutate: the unmutated tests fail:\n  ' + '\n  '.join(bad))
            return 2
        print('mutate: unmutated build and tests ok (%.0f s); %d mutants' % (time.time() - started, len(chosen)),
              flush=True)
        results = []
        for k, m in enumerate(chosen, 1):
            t0 = time.time()
            if m.equivalent and not args.equivalent:
                r = ('equivalent', [], m.equivalent)
            else:
                r = run_mutant(suite, m, args.full)
            results.append((m, r))
            status = {'caught': 'caught by ' + ', '.join(r[1]), 'missed': 'MISSED',
                      'equivalent-object': 'equivalent (no object changed)',
                      'no-build': 'DOES NOT BUILD', 'equivalent': 'equivalent (not run)'}[r[0]]
            tag = ' [pending]' if m.pending else ''
            print('[%2d/%d] %-32s %-22s %s%s (%.0f s)' % (k, len(chosen), m.id, area_of(m.file), status, tag,
                                                        time.time() - t0), flush=True)
            if r[0] in ('caught', 'missed', 'no-build') and r[2]:
                print('        %s' % r[2], flush=True)
        pct = summarise(results, print)
        print('\nmutate: %d mutants in %.0f s' % (len(chosen), time.time() - started))
        if any(r[0] == 'no-build' for _, r in results):
            return 2
        if args.min is not None and pct is not None and pct < args.min:
            print('mutate: %.1f%% caught, below --min %.1f%%' % (pct, args.min))
            return 1
        return 0
    finally:
        if tmp:
            shutil.rmtree(tmp, ignore_errors=True)


if __name__ == '__main__':
    sys.exit(main())
