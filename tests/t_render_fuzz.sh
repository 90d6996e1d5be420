#!/bin/sh
# t_render_fuzz.sh: locus-render on mutated gallery scenes (fixed seed): every run must end with
# status 0 or 65 within 20 s, never a crash, a sanitizer report or a hang.
. tests/lib.sh
if ! command -v python3 >/dev/null 2>&1; then ok "python3 missing: fuzz skipped"; done_tests; fi
python3 - "$BIN/locus-render" "$T" <<'PY'
import glob, random, subprocess, sys
render, tmp = sys.argv[1], sys.argv[2]
random.seed(20261122)
seeds = sorted(glob.glob('fixtures/scenes/*.scene') + glob.glob('fixtures/render/*.scene'))
texts = []
for f in seeds:
    s = open(f).read()
    for big, small in (('size 1024 768', 'size 32 24'), ('size 640 480', 'size 32 24'), ('size 480 360', 'size 32 24'),
                       ('size 480 480', 'size 24 24'), ('size 400 400', 'size 24 24'), ('size 400 300', 'size 32 24'),
                       ('size 640 320', 'size 32 16'), ('depth 10', 'depth 5')):
        s = s.replace(big, small)
    texts.append(s)
tokens = ['nan', 'inf', '-1', '0', '1e308', '1e-308', '#', 'end', 'object', 'shape', 'render', 'view', 'c', 'x', '(',
          ')', '^', '/0', '99999', 'weight', 'bound', 'points', 'voronoi', 'distance-to', 'sqrt(-1)', '1/x',
          'floor(x)', 'tan(y)', '\t', '\n', '0.0000001']
bad = 0
for i in range(60):
    w = random.choice(texts).split(' ')
    for _ in range(random.randint(1, 4)):
        j, op = random.randrange(len(w)), random.random()
        if op < 0.4: w[j] = random.choice(tokens)
        elif op < 0.6: del w[j]
        elif op < 0.8: w.insert(j, random.choice(tokens))
        else: w[j] = w[j][::-1]
    open(tmp + '/f.scene', 'w').write(' '.join(w))
    try:
        r = subprocess.run([render, tmp + '/f.scene', '-o', tmp + '/f.meta', '--quiet'], capture_output=True, timeout=20)
        if r.returncode not in (0, 65):
            bad += 1
            print('not ok - mutation %d: exit %d: %s' % (i, r.returncode, r.stderr.decode(errors='replace')[-300:]))
    except subprocess.TimeoutExpired:
        bad += 1
        print('not ok - mutation %d: no answer within 20 s' % i)
if not bad:
    print('ok - 60 mutated scenes: each rendered (0) or refused (65)')
sys.exit(1 if bad else 0)
PY
[ $? = 0 ] || FAILED=1
done_tests
