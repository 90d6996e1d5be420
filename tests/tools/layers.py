#!/usr/bin/env python3
"""layers.py: the folder rule of drivers/ (docs/drivers.md, "Layers") read from the #include lines,
and the count of circles and upward includes the architecture issue measures.

  layers.py check ALLOWFILE [OBJDIR]
                              print "ok - ..."/"not ok - ..." lines (tests/t_layers.sh); exit 1 on a
                              failure. With OBJDIR (its objects built), the circles are checked too.
  layers.py count [OBJDIR]    print the circles (objects that need each other, from nm of OBJDIR,
                              default build/native), the upward includes and, for information, the
                              upward symbol uses (nm), then one summary line

An upward include is an #include line that breaks the rule (a folder using one it may not, an
_int.h read outside its folder, or libcore/libmeta reading a drivers/ header). A circle is a set
of two or more source files whose objects need each other's symbols (a strongly connected
component of the graph "a.o uses a symbol b.o defines"). Run from the top of the tree.
"""
import os, re, subprocess, sys

BASE = {'util'}
LOW = BASE | {'io', 'geom', 'quant', 'hpgl/read'}
FRAME = BASE | {'io', 'geom', 'render', 'device'}
FAMILIES = ('raster', 'svg', 'fb', 'ps', 'hpgl', 'film')
# folder -> the folders it may include from (besides itself)
ALLOWED = {
    'util': set(),
    'io': BASE, 'geom': BASE, 'quant': BASE, 'hpgl/read': BASE,
    'image': BASE | {'io'},
    'render': BASE | {'geom'},
    'device': FRAME - {'device'},
    'raster': FRAME | {'image'}, 'film': FRAME | {'image'}, 'fb': FRAME | {'quant'},
    'svg': FRAME | {'image'}, 'ps': FRAME, 'hpgl': FRAME | {'hpgl/read'},
    'diff': FRAME | LOW | {'image'} | set(FAMILIES),
    'import': FRAME | LOW | {'image'} | set(FAMILIES),
    'cli': None,                       # anything
    'printer': None,                   # the PAPPL printer application: a program, as cli
}
INC = re.compile(r'^\s*#\s*include\s*"([^"]+)"', re.M)


def sources(top):
    out = []
    for d, _, fs in os.walk(top):
        out += [os.path.join(d, f) for f in fs if f.endswith(('.c', '.h'))]
    return sorted(out)


def folder(path):                      # drivers/hpgl/read/x.c -> hpgl/read, drivers/io/x.c -> io
    parts = path.split('/')[1:-1]
    return '/'.join(parts) if parts else ''


def includes(path):
    text = open(path, errors='replace').read()
    for m in INC.finditer(text):
        yield text.count('\n', 0, m.start()) + 1, m.group(1)


def drv_headers():
    hs = [p for p in sources('drivers') if p.endswith('.h')]
    by_name = {}
    for h in hs:
        by_name.setdefault(os.path.basename(h), []).append(h)
    return set(hs), by_name


def scan():
    """Every include line of drivers/, core/ and meta/ that reaches a drivers/ header:
    (file, line, included path, problem or None)."""
    hs, by_name = drv_headers()
    rows = []
    for f in sources('drivers') + sources('core') + sources('meta'):
        for line, inc in includes(f):
            local = os.path.join(os.path.dirname(f), inc)
            if f.startswith('drivers/'):
                if '/' in inc and 'drivers/' + inc in hs:
                    target, qualified = 'drivers/' + inc, True
                elif inc in by_name:
                    target, qualified = by_name[inc][0], False
                else:
                    continue               # system, meta or core header
            else:
                if os.path.exists(local) or inc not in by_name:
                    continue               # its own module's header
                target, qualified = by_name[inc][0], True
            rows.append((f, line, target, problem(f, target, qualified)))
    return rows


def is_program(f):                     # the mains of core/ and meta/ are programs: the cli layer
    return f in ('core/locus-render.c', 'meta/locus-meta.c')


def problem(f, target, qualified):
    tf = folder(target)
    if not f.startswith('drivers/'):
        if is_program(f):
            return None if not target.endswith('_int.h') else 'an _int.h read outside its folder'
        return 'libcore/libmeta use nothing in drivers/'
    if not qualified:
        return 'not path-qualified (write "%s")' % target[len('drivers/'):]
    ff = folder(f)
    if target.endswith('_int.h') and tf != ff:
        return 'an _int.h read outside its folder'
    if ff not in ALLOWED:
        return 'folder %s has no layer in the rule' % (ff or 'drivers/')
    ok = ALLOWED[ff]
    if ok is None or tf == ff or tf in ok:
        return None
    return '%s may not use %s' % (ff, tf)


def load_allow(path):
    """Lines "FILE -> HEADER  # why" (an include) and "circle: FILE FILE ...  # why"."""
    allow, circles = {}, {}
    for ln in open(path):
        ln = ln.strip()
        if not ln or ln.startswith('#'):
            continue
        rule, _, why = ln.partition('#')
        if rule.startswith('circle:'):
            circles[frozenset(rule[len('circle:'):].split())] = why.strip()
            continue
        src, _, inc = rule.partition('->')
        allow[(src.strip(), inc.strip())] = why.strip()
    return allow, circles


def check(allowfile, objdir=None):
    allow, allowed_circles = load_allow(allowfile)
    rows = scan()
    failed = 0

    def report(good, text):
        nonlocal failed
        print(('ok - ' if good else 'not ok - ') + text)
        failed |= not good

    seen = set()
    bad = []
    for f, line, target, prob in rows:
        if not prob:
            continue
        key = (f, target[len('drivers/'):])
        if key in allow and 'not path-qualified' not in prob:
            seen.add(key)
            continue
        bad.append('%s:%d: #include "%s": %s' % (f, line, key[1], prob))
    unq = [b for b in bad if 'not path-qualified' in b]
    rest = [b for b in bad if 'not path-qualified' not in b]
    report(not unq, 'every #include of a drivers/ header in drivers/ is path-qualified (%d lines read)' % len(rows))
    for b in unq:
        print('#   ' + b)
    report(not rest, 'every #include follows the layer rule of docs/drivers.md, but for the %d allowed below' % len(seen))
    for b in rest:
        print('#   ' + b)
    for key, why in sorted(allow.items()):
        if key in seen:
            print('#   allowed until phase 2: %s -> %s (%s)' % (key[0], key[1], why))
    stale = sorted(set(allow) - seen)
    report(not stale, 'the allow-list names only includes that still break the rule')
    for key in stale:
        print('#   stale: %s -> %s: remove it from the list' % key)
    known = [p for p in sources('drivers') if folder(p) not in ALLOWED]
    report(not known, 'every file of drivers/ is in a folder the rule knows')
    for p in known:
        print('#   ' + p)
    if objdir:
        g = nm_graph(objdir)
        if not g:
            print('ok - circles # SKIP no objects in %s' % objdir)
        else:
            found = {frozenset(c) for c in sccs(g)}
            new = [c for c in found if c not in allowed_circles]
            report(not new, 'no circle of objects that need each other beyond the %d listed (%d objects read)'
                   % (len(found) - len(new), len(g)))
            for c in sorted(sorted(c) for c in new):
                print('#   new circle: ' + ' '.join(c))
            for c in sorted(found & set(allowed_circles), key=sorted):
                print('#   allowed until phase 2: circle %s (%s)' % (' '.join(sorted(c)), allowed_circles[c]))
            stale = sorted(sorted(c) for c in set(allowed_circles) - found)
            report(not stale, 'the allow-list names only circles that are still there')
            for c in stale:
                print('#   stale: circle ' + ' '.join(c) + ': remove it from the list')
    # the rule itself must be able to fail: a made-up include upward is refused
    report(problem('drivers/geom/x.c', 'drivers/device/device.h', True) is not None and
           problem('drivers/svg/x.c', 'drivers/ps/psdev.h', True) is not None and
           problem('drivers/diff/x.c', 'drivers/image/imgread_int.h', True) is not None and
           problem('core/x.c', 'drivers/io/transport.h', True) is not None,
           'the rule refuses an include upward, between families, of an _int.h, and from libcore')
    return failed


def nm_graph(objdir):
    objs = []
    for top in ('drivers', 'core', 'meta'):
        for d, _, fs in os.walk(os.path.join(objdir, top)):
            objs += [os.path.join(d, f) for f in fs if f.endswith('.o')]
    defs, uses = {}, {}
    for o in sorted(objs):
        src = os.path.relpath(o, objdir)[:-2] + '.c'
        if not os.path.exists(src):
            continue                        # a stale object of a moved file
        out = subprocess.run(['nm', '-P', o], capture_output=True, text=True).stdout
        uses[src] = set()
        for ln in out.splitlines():
            p = ln.split()
            if len(p) < 2:
                continue
            if p[1] == 'U':
                uses[src].add(p[0])
            elif p[1] in 'TDBRC' or p[1] in 'VW':
                defs.setdefault(p[0], src)
    return {s: {defs[u] for u in us if u in defs and defs[u] != s} for s, us in uses.items()}


def sccs(g):
    index, low, stack, on, out, n = {}, {}, [], set(), [], [0]
    def visit(v):                           # Tarjan, iterative
        work = [(v, iter(sorted(g.get(v, ()))))]
        index[v] = low[v] = n[0]; n[0] += 1; stack.append(v); on.add(v)
        while work:
            u, it = work[-1]
            for w in it:
                if w not in index:
                    index[w] = low[w] = n[0]; n[0] += 1; stack.append(w); on.add(w)
                    work.append((w, iter(sorted(g.get(w, ())))))
                    break
                if w in on:
                    low[u] = min(low[u], index[w])
            else:
                work.pop()
                if work:
                    low[work[-1][0]] = min(low[work[-1][0]], low[u])
                if low[u] == index[u]:
                    c = []
                    while True:
                        w = stack.pop(); on.discard(w); c.append(w)
                        if w == u:
                            break
                    if len(c) > 1:
                        out.append(sorted(c))
    for v in sorted(g):
        if v not in index:
            visit(v)
    return sorted(out)


def upward_uses(g):
    """Edges of the object graph that go against the rule (a symbol, not an include)."""
    out = []
    for a in sorted(g):
        for b in sorted(g[a]):
            if not b.startswith('drivers/'):
                continue
            if not a.startswith('drivers/'):
                if not is_program(a):
                    out.append((a, b))
                continue
            ok = ALLOWED.get(folder(a), set())
            if ok is not None and folder(b) != folder(a) and folder(b) not in ok:
                out.append((a, b))
    return out


def count(objdir):
    g = nm_graph(objdir)
    circles = sccs(g)
    for c in circles:
        print('circle (%d files): %s' % (len(c), ' '.join(c)))
    up = [r for r in scan() if r[3] and 'not path-qualified' not in r[3]]
    for f, line, target, prob in up:
        print('upward: %s:%d -> %s (%s)' % (f, line, target[len('drivers/'):], prob))
    uses = upward_uses(g)
    for a, b in uses:
        print('upward use (nm): %s -> %s' % (a, b))
    print('circles=%d upward_includes=%d upward_uses=%d' % (len(circles), len(up), len(uses)))
    return 0


if __name__ == '__main__':
    if len(sys.argv) >= 3 and sys.argv[1] == 'check':
        sys.exit(check(sys.argv[2], sys.argv[3] if len(sys.argv) > 3 else None))
    if len(sys.argv) >= 2 and sys.argv[1] == 'count':
        sys.exit(count(sys.argv[2] if len(sys.argv) > 2 else 'build/native'))
    sys.exit(__doc__)
