#!/usr/bin/python3
"""Command-line fuzzer for granular-dsmc / granular-theory.

usage: python3 tests/fuzz/cli_fuzz.py [--bin build/bin] [--minutes M] [--seed S] [--root DIR] [--keep]
(needs h5py and numpy: python3-h5py, python3-numpy; see tests/fuzz/README.md)

Every case runs in a fresh folder ROOT/cases/NNNNNN (deleted afterwards unless it produced a finding
or --keep).  Runs are serial, under `nice -n 19`, with a 60 s timeout (then SIGINT, 5 s, SIGKILL of the
process group) and RLIMIT_AS = 6 GB.  Findings (deduplicated by kind + normalised message) go to
ROOT/findings.jsonl, every case to ROOT/cases.jsonl, every distinct error message to ROOT/messages.jsonl.
Literal /dev/null is only used inside a private mount namespace (unshare -m) with a tmpfs /dev, since
the fuzzer runs as root.
"""
import argparse, csv, hashlib, io, json, math, os, random, re, resource, shutil, signal, stat
import subprocess, sys, threading, time

# Set from the command line (--bin) in __main__; the examples of this repository.
DSMC = 'build/bin/granular-dsmc'
THEORY = 'build/bin/granular-theory'
EXAMPLES = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'examples')
TIMEOUT = 60
MEMLIMIT = 6 * 1024 ** 3

EXC_PATTERNS = ['std::', 'terminate called', 'what():', 'basic_string', 'map::at', '_M_range_check',
                'stoi', 'stod', 'stol', 'bad_alloc', 'Assertion', 'Segmentation', 'HDF5-DIAG',
                'core dumped', 'MPI_ABORT', 'runtime error:', 'AddressSanitizer', 'double free',
                'free(): ', 'malloc(): ', 'stack smashing', 'out_of_range', 'invalid_argument',
                'length_error', 'logic_error', 'filesystem error', 'bad_variant', 'bad_optional']

# --------------------------------------------------------------------------------------------------
def sh(cmd, **kw):
    return subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, **kw)

def limits():
    resource.setrlimit(resource.RLIMIT_AS, (MEMLIMIT, MEMLIMIT))
    resource.setrlimit(resource.RLIMIT_CORE, (0, 0))

def parse_defaults(text):
    groups, cur = {}, None
    for line in text.splitlines():
        s = line.strip()
        m = re.match(r'!?\s*&(\w+)', s)
        if m:
            cur = m.group(1); groups.setdefault(cur, []); continue
        if cur is None:
            continue
        m = re.match(r'!?\s*(\w+)\s*=\s*(.*?)\s*(!.*)?$', s)
        if m and not s.startswith('! ') or (m and s.startswith('! ') and re.match(r'!\s\w+\s+=', s)):
            if m.group(1) not in [n for n, _ in groups[cur]]:
                groups[cur].append((m.group(1), m.group(2)))
    return groups

NUMS = ['0', '-0', '1', '-1', '2', '3', '0.5', '0.9', '1.0', '1.5', '10', '100', '1d300', '1D-300', '1e309',
        '-1e309', '1e-320', '1e100', '1e-100', '1e101', '1e-101', '1.0d0', '1.0_8', '.5', '5.', '+3', '1e',
        '1.2.3', '0x10', '2147483647', '2147483648', '4294967297', '9223372036854775807',
        '9223372036854775808', '-2147483649', '1e10', '1e12', '1e18', '1e19', 'nan', 'NaN', 'inf', '-inf',
        'Infinity', '1.0e+00', '0.0', '-0.0', '1e-5', '0.99999999999999999', '1.0000000000000002', '64',
        '63', '65', '32768', '1,', '(1.0,2.0)', '1 2', '1e0x', '٣', '１']
LOGS = ['.true.', '.false.', 'T', 'F', '.t.', '.f.', 'yes', '.TRUE.x', 'true', '.true', '1']
STRS = ["'majorant'", "'pairs'", "'lowrank'", "'constant'", "'viscoelastic'", "'log'", "'linear'", "''",
        "'", "'unterminated", '"dq"', "'a''b'", "'x.h5'", "'system:restitution'", "'system:mass(2)'",
        "'system:restitution(1,2)'", "'nope:var'", "'gaussian'", "'white_noise'", "'none'", "'shell'",
        "'cube'", "'maxwell'", "'list'", "'cube_root'", "'power'", "'dsmc:n_particles'",
        "'initial:temperature'", "'output:n_samples'", "'system:restitution(2,2)'", "'system:mass(0)'",
        "'system:mass(1,2)'", "'0.01, 0.02'", "'a!b.h5'", "'sub/dir/x.h5'", "'/dev/null'", "'ü.h5'",
        "'" + 'y' * 300 + "'", "'dsmc:seed'", "'system:n_species'", "'shear:rate'",
        "'thermostat:kind'", "'output:file'", "'dsmc:scheme'", "'system:enskog'"]
ARRS = ['1.0, 2.0', '0.5,0.6,0.7', '1,,2', '3*', '*', '2*', '0*1', '-1*2', '3*1.0', '2*0.5', '1000000000*1.0',
        '2*0.5, 0.7', '1 2 3', '1.0, 2.0, 3.0, 4.0, 5.0', '0.3, 0.5, 0.9', '1e-3, 1e-2, 1e-1', '5*',
        '2147483648*1', '1*', ', 1', '1;2', "'a', 'b'", '0.9, 0.8, 0.7, 0.6, 0.5, 0.4, 0.3, 0.2, 0.1']

def rand_value(r, name=''):
    k = r.random()
    if name in ('n_particles', 'replicas', 'n_samples', 'block_size', 'histogram_bins', 'reduced_bins') \
            and k < 0.5:
        return r.choice(['0', '1', '2', '3', '-1', '64', '100', '500', '2000', '2e3', '1.5', '20000',
                         '1e9', '2147483648', "'x'", '.true.', '3*2'])
    if name in ('t_end', 'collisions_per_particle') and k < 0.5:
        return r.choice(['0', '-1', '1e-300', '0.001', '1', '5', '10', '50', '1e300', 'nan', '1d3'])
    if k < 0.45: return r.choice(NUMS)
    if k < 0.55: return r.choice(LOGS)
    if k < 0.80: return r.choice(STRS)
    if k < 0.97: return r.choice(ARRS)
    return r.choice(['', ' ', '!', '/', '&', '=', '= 1'])

def misspell(r, s):
    if not s: return 'x'
    op = r.randrange(6)
    i = r.randrange(len(s))
    if op == 0: return s[:i] + s[i + 1:]
    if op == 1 and len(s) > 1:
        j = min(i + 1, len(s) - 1); l = list(s); l[i], l[j] = l[j], l[i]; return ''.join(l)
    if op == 2: return s + r.choice(['s', '_', '1', 'x'])
    if op == 3: return s.upper()
    if op == 4: return s.replace('_', '')
    return s[:i] + r.choice('abcdefghijklmnopqrstuvwxyz_') + s[i:]

# --------------------------------------------------------------------------------------------------
class Fuzzer:
    def __init__(self, root, seed, keep):
        self.root = root; self.keep = keep
        self.r = random.Random(seed)
        self.cases_dir = os.path.join(root, 'cases'); os.makedirs(self.cases_dir, exist_ok=True)
        self.pool = os.path.join(root, 'pool'); os.makedirs(self.pool, exist_ok=True)
        self.findings_path = os.path.join(root, 'findings.jsonl')
        self.cases_log = open(os.path.join(root, 'cases.jsonl'), 'a')
        self.msgs_path = os.path.join(root, 'messages.jsonl')
        self.seen = {}
        if os.path.exists(self.findings_path):
            for line in open(self.findings_path):
                try: self.seen[json.loads(line)['key']] = 1
                except Exception: pass
        self.msgs = {}
        if os.path.exists(self.msgs_path):
            for line in open(self.msgs_path):
                try: self.msgs[json.loads(line)['key']] = 1
                except Exception: pass
        self.stats = {}
        self.ncase = max([int(d) for d in os.listdir(self.cases_dir) if d.isdigit()] + [0])
        d = sh([DSMC, '--print-defaults']).stdout.decode()
        self.defaults_text = d
        self.groups = parse_defaults(d)
        self.varnames = [(g, n) for g, l in self.groups.items() for n, _ in l]
        obs = sh([DSMC, '--print-observables']).stdout.decode()
        self.observables = re.findall(r'^\| `(\w+)`', obs, re.M)
        self.bases = {}
        for dp, _, fs in os.walk(EXAMPLES):
            for f in fs:
                if f.endswith('.nml'):
                    self.bases[f] = open(os.path.join(dp, f), encoding='utf-8', errors='replace').read()
        self.bases['defaults.nml'] = d
        self.make_pool()

    # ---------------------------------------------------------------- pool of files for --restart/--table
    def small(self, text, name):
        r = self.r
        n = '40000' if 'polydisperse' in name else str(r.choice([500, 1000, 2000, 2000, 3000, 4000]))
        text = re.sub(r'(n_particles\s*=\s*)[^!\n]*', lambda m: m.group(1) + n + ' ', text)
        text = re.sub(r'(replicas\s*=\s*)[^!\n]*', lambda m: m.group(1) + str(r.choice([1, 2, 2, 3, 4])) + ' ',
                      text)
        if 'polydisperse' in name:
            text = re.sub(r'(n_species\s*=\s*)\d+', r'\g<1>20', text)
        return text

    def make_pool(self):
        p = self.pool
        if os.path.exists(os.path.join(p, 'done')):
            return
        def run(nml, out, extra=()):
            open(os.path.join(p, out + '.nml'), 'w').write(nml)
            res = sh(['nice', '-n', '19', DSMC, out + '.nml', '--quiet', '--force', '--output', out + '.h5']
                     + list(extra), cwd=p, timeout=120, preexec_fn=limits)
            print('pool', out, res.returncode, res.stderr.decode()[-300:], file=sys.stderr)
        B = self.bases
        sub = lambda t, a, b: re.sub(a, b, t)
        run(sub(B['haff.nml'], r'n_particles\s*=\s*\d+', 'n_particles = 2000'), 'plain')
        run(sub(sub(B['haff.nml'], r'n_particles\s*=\s*\d+', 'n_particles = 2000'),
                r'replicas\s*=\s*\d+', 'replicas = 1'), 'onerep')
        run(sub(B['binary-hcs.nml'], r'n_particles\s*=\s*\d+', 'n_particles = 3000'), 'binary')
        run(sub(B['sweep.nml'], r'n_particles\s*=\s*\d+', 'n_particles = 2000'), 'sweep')
        run(sub(B['agg-frag.nml'], r'n_particles\s*=\s*\d+', 'n_particles = 3000'), 'agg')
        run(sub(B['usf.nml'], r'n_particles\s*=\s*\d+', 'n_particles = 2000'), 'usf')
        run(sub(B['rough-cooling.nml'], r'n_particles\s*=\s*\d+', 'n_particles = 2000'), 'rough')
        run(sub(B['msd-binary.nml'], r'n_particles\s*=\s*\d+', 'n_particles = 2000'), 'msd')
        snap = sub(sub(B['haff.nml'], r'n_particles\s*=\s*\d+', 'n_particles = 2000'), r't_end\s*=\s*[\d.]+',
                   't_end = 100.0')
        snap = snap.replace("first_sample   = 1.0", "first_sample = 1.0\n  snapshot_times = 50.0, 100.0")
        run(snap, 'snap')
        # a checkpoint of an interrupted run
        ck = sub(B['sweep.nml'], r'n_particles\s*=\s*\d+', 'n_particles = 60000')
        ck = sub(ck, r'checkpoint_every\s*=\s*[\d.]+', 'checkpoint_every = 0.05')
        open(os.path.join(p, 'ckpt.nml'), 'w').write(ck)
        pr = subprocess.Popen(['nice', '-n', '19', DSMC, 'ckpt.nml', '--quiet', '--force'], cwd=p,
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, preexec_fn=limits)
        time.sleep(1.5); pr.send_signal(signal.SIGINT); o, e = pr.communicate(timeout=60)
        print('pool ckpt rc', pr.returncode, e.decode()[-300:], os.listdir(p), file=sys.stderr)
        # corrupt / crafted files
        data = open(os.path.join(p, 'plain.h5'), 'rb').read()
        open(os.path.join(p, 'trunc.h5'), 'wb').write(data[:len(data) // 2])
        open(os.path.join(p, 'head.h5'), 'wb').write(data[:512])
        rr = random.Random(7)
        b = bytearray(data)
        for _ in range(64):
            i = rr.randrange(2048, len(b)); b[i] ^= 1 << rr.randrange(8)
        open(os.path.join(p, 'flip.h5'), 'wb').write(bytes(b))
        open(os.path.join(p, 'text.h5'), 'w').write('not an hdf5 file\n')
        open(os.path.join(p, 'empty.h5'), 'w').close()
        import h5py, numpy as np
        with h5py.File(os.path.join(p, 'foreign.h5'), 'w') as f:
            f['x'] = np.arange(3)
        for name, mut in [('nopar', 'nopar'), ('badshape', 'badshape'), ('strval', 'strval'),
                          ('badnml', 'badnml'), ('noobs', 'noobs'), ('nantime', 'nantime')]:
            dst = os.path.join(p, name + '.h5'); shutil.copy(os.path.join(p, 'plain.h5'), dst)
            with h5py.File(dst, 'a') as f:
                if mut == 'nopar': del f['parameters']
                elif mut == 'badshape':
                    del f['observables/temperature/value']; f['observables/temperature/value'] = np.zeros((2, 3, 4))
                elif mut == 'strval':
                    del f['observables/total_temperature/value']
                    f['observables/total_temperature/value'] = np.array([b'a', b'b'])
                elif mut == 'badnml':
                    for k in list(f['parameters'].attrs):
                        if 'namelist' in k: f['parameters'].attrs[k] = '&system mass = oops /\n'
                elif mut == 'noobs': del f['observables']
                elif mut == 'nantime':
                    t = f['observables/temperature/time']; a = t[...]; a[1] = np.nan; t[...] = a
        open(os.path.join(p, 'done'), 'w').write('1')

    def pool_files(self):
        return sorted(f for f in os.listdir(self.pool) if f.endswith('.h5'))

    # ---------------------------------------------------------------- namelist mutation
    def mutate_nml(self, text, case):
        r = self.r
        lines = text.split('\n')
        nmut = r.choice([0, 0, 0, 0, 0, 1, 1, 1, 2, 2, 3, 4, 6])
        for _ in range(nmut):
            op = r.randrange(22)
            i = r.randrange(len(lines)) if lines else 0
            if not lines: lines = ['']
            if op == 0: del lines[i]
            elif op == 1: lines.insert(i, lines[i])
            elif op == 2:
                j = r.randrange(len(lines)); lines[i], lines[j] = lines[j], lines[i]
            elif op in (3, 4, 5):
                idx = [k for k, l in enumerate(lines) if re.match(r'\s*\w+(\([^)]*\))?\s*=', l)]
                if idx:
                    k = r.choice(idx); m = re.match(r'(\s*(\w+)(\([^)]*\))?\s*=\s*)', lines[k])
                    lines[k] = m.group(1) + rand_value(r, m.group(2))
            elif op in (6, 7):
                g, n = r.choice(self.varnames)
                gi = [k for k, l in enumerate(lines) if l.strip().lower().startswith('&' + g)]
                if not gi or r.random() < 0.2:
                    gi = [k for k, l in enumerate(lines) if l.strip().startswith('&')] or [0]
                k = r.choice(gi) + 1
                lhs = n
                if op == 7:
                    lhs = n + r.choice(['(1)', '(2)', '(0)', '(-1)', '(1,2)', '(2,1)', '(2,2)', '(3)', '(99999999999)',
                                        '(1:2)', '(1,2,3)', '()', '(a)', '(1, 2)', '(200)', '(201,1)'])
                if r.random() < 0.15: lhs = misspell(r, lhs)
                lines.insert(k, '  %s = %s' % (lhs, rand_value(r, n)))
            elif op == 8:
                idx = [k for k, l in enumerate(lines) if re.match(r'\s*\w+', l)]
                if idx:
                    k = r.choice(idx); m = re.match(r'(\s*)(\w+)(.*)', lines[k], re.S)
                    lines[k] = m.group(1) + misspell(r, m.group(2)) + m.group(3)
            elif op == 9:
                idx = [k for k, l in enumerate(lines) if l.strip() == '/']
                if idx: del lines[r.choice(idx)]
                else: lines.insert(i, '/')
            elif op == 10:
                lines.insert(i, r.choice(['/', '&', '&end', '$end', '&system', '&SYSTEM', '& system', '&nosuch',
                                          '&nosuch\n/', '&system /', '&dsmc\n/', '&output file = \'z.h5\' /']))
            elif op == 11:
                idx = [k for k, l in enumerate(lines) if l.strip().startswith('&')]
                if idx:
                    k = r.choice(idx); j = k
                    while j < len(lines) and lines[j].strip() != '/': j += 1
                    lines[j + 1:j + 1] = lines[k:j + 1]
            elif op == 12:
                lines.insert(i, r.choice(['\x00', '\xff\xfe garbage', '\t\tmass\t=\t1.0', 'x' * 100000,
                                          '  mass = ' + '1.0, ' * 5000 + '1.0', '!' * 10, "! it's a 'comment",
                                          '  mass = 1.0 diameter = 1.0', '  mass = 1.0, diameter = 1.0',
                                          '  mass = 1.0; diameter = 1.0', '  = 1.0', '  mass ==1', 'mass',
                                          '  file = \'a!b.h5\'  ! bang in string', '\u00a0mass = 1.0',
                                          '  restitution(1,2) = 0.5', '  temperature(2) = 2.0', '\ufeff',
                                          '  mass = 1.0 /', '/ extra', '& /']))
            elif op == 13:
                if r.random() < 0.5: lines = lines[:i]
                else:
                    t = '\n'.join(lines); t = t[:r.randrange(len(t) + 1)]; lines = t.split('\n')
            elif op == 14:
                lines = [l.upper() for l in lines]
            elif op == 15:
                lines.append(r.choice([
                    "&sweep variable = 'system:restitution', values = 0.5, 0.9 /",
                    "&sweep variable = %s, values = %s /" % (r.choice(STRS), r.choice(ARRS)),
                    "&sweep variable = 'system:restitution(1,2)', 'system:mass(2)'\n values(1,1) = 0.6, 0.8\n values(1,2) = 2.0, 4.0\n grid = .true. /",
                    "&sweep variable = 'system:number_density', values = '0.01, 0.02', '0.02, 0.04' /",
                    "&sweep variable = 'system:restitution', 'system:restitution' values = 0.5, 0.6 /",
                    "&sweep variable = 'output:file', values = 'a.h5', 'b.h5' /",
                    "&sweep variable = 'dsmc:n_particles', values = 1000, 2000 /",
                    "&sweep variable = 'system:n_species', values = 1, 2 /",
                    "&sweep variable = 'initial:temperature', values = 1.0, 1e-300, 0 /",
                    "&sweep variable = 'dsmc:scheme', values = 'pairs', 'lowrank', 'majorant' /",
                ]))
            elif op == 16:
                lines.append(r.choice([
                    "&agg_frag aggregation_energy = 0.5, fragmentation_energy = 1.5, fragment_restitution = 0.5 /",
                    "&agg_frag aggregation_energy = %s /" % r.choice(NUMS),
                    "&thermostat kind = 'gaussian' /", "&thermostat kind = 'white_noise', noise_strength = %s /" % r.choice(NUMS),
                    "&shear rate = %s /" % r.choice(NUMS), "&shear rate = 0.01, average_from = %s /" % r.choice(NUMS),
                    "&system roughness = %s /" % r.choice(NUMS),
                ]))
            elif op == 17:
                lines = [l + '\r' for l in lines]
            elif op == 18:
                src = r.choice(['snap.h5', 'plain.h5', 'sweep.h5', 'trunc.h5', 'text.h5', 'agg.h5', 'rough.h5',
                                'foreign.h5', 'nopar.h5', 'binary.h5', 'missing.h5'])
                if os.path.exists(os.path.join(self.pool, src)):
                    shutil.copy(os.path.join(self.pool, src), os.path.join(case, 'from_' + src))
                gi = [k for k, l in enumerate(lines) if l.strip().lower().startswith('&initial')]
                if gi: lines.insert(gi[0] + 1, "  from_file = 'from_%s'" % src)
                if r.random() < 0.7:
                    lines = [l for l in lines if not re.match(r'\s*(temperature|distribution)\s*=', l)]
            elif op == 19:
                idx = [k for k, l in enumerate(lines) if re.match(r'\s*t_end', l)]
                for k in idx: lines[k] = '  collisions_per_particle = %s' % r.choice(['5', '20', '1e-9', '0'])
            elif op == 20:
                gi = [k for k, l in enumerate(lines) if l.strip().lower().startswith('&output')]
                if gi: lines.insert(gi[0] + 1, r.choice([
                    '  checkpoint_every = %s' % r.choice(['0', '0.01', '-1', '1e300', 'nan', '0.001']),
                    '  snapshot_times = %s' % r.choice(ARRS + NUMS), '  sample_times = %s' % r.choice(ARRS + NUMS),
                    '  track_displacements = .true.', '  msd_start_temperature = 0.5', '  msd_start_time = %s' % r.choice(NUMS),
                    "  spacing = 'log'", '  first_sample = %s' % r.choice(NUMS), '  n_samples = %s' % r.choice(NUMS),
                    "  author = %s" % r.choice(STRS), '  histogram_bins = %s' % r.choice(NUMS)]))
            else:
                lines.insert(i, r.choice(['', '!', '  ! comment', '! &system', '&system ! / inside']))
        return '\n'.join(lines)

    # ---------------------------------------------------------------- pieces of the command line
    def rand_set(self, small_only=False):
        r = self.r
        g, n = r.choice(self.varnames)
        if r.random() < 0.1: g = misspell(r, g)
        if r.random() < 0.1: n = misspell(r, n)
        lhs = '%s:%s' % (g, n)
        k = r.random()
        if k < 0.05: lhs = n
        elif k < 0.08: lhs = ':' + n
        elif k < 0.10: lhs = g + ':'
        elif k < 0.12: lhs = '%s.%s' % (g, n)
        elif k < 0.18: lhs += r.choice(['(1)', '(2)', '(1,2)', '(0)', '(3,3)', '(', ')', '(x)'])
        elif k < 0.20: lhs = '&' + lhs
        val = rand_value(r, n)
        k = r.random()
        if k < 0.04: return lhs
        if k < 0.07: return lhs + '='
        if k < 0.10: return lhs + ' = ' + val
        if k < 0.12: return lhs + '==' + val
        return lhs + '=' + val

    SEM = {
        'system:n_species': ['1', '2', '3', '8'], 'system:mass': ['1e-100', '1e100', '1e50', '1e-50', '0.001', '1000', '1.0, 1e6', '2*1.0', '1.0, 2.0, 3.0'],
        'system:diameter': ['1e-100', '1e-30', '1e30', '0.001', '1000', '1.0, 0.01'],
        'system:number_density': ['1e-100', '1e-30', '0.3', '0.49', '0.6', '1e-6', '0.01, 1e-9'],
        'system:restitution': ['0', '0.0', '0.01', '0.5', '0.99', '1', '1.0', '-0', '1e-300', '0.999999999'],
        'system:restitution(1,2)': ['0', '1', '0.3'], 'system:restitution_model': ["'viscoelastic'", "'constant'"],
        'system:visco_a_kappa': ['0', '1e-9', '0.09', '10', '1e10'], 'system:enskog': ['.true.'],
        'system:mass_law': ["'linear'"], 'system:diameter_law': ["'cube_root'"], 'system:density_law': ["'power'"],
        'system:density_exponent': ['0', '1.5', '-3', '100'], 'system:roughness': ['-1', '1', '0', '0.5', '-0.999', '0.999999'],
        'system:moment_of_inertia': ['0', '1e-9', '0.4', '0.6667', '1', '1e9'],
        'initial:temperature': ['1e-100', '1e100', '1e-40', '1e-20', '0', '1e20', '1.0, 1e-10', '2*1.0'],
        'initial:distribution': ["'shell'", "'cube'", "'maxwell'"],
        'initial:rotational_temperature': ['0', '1e-30', '100', '1e-100'],
        'dsmc:scheme': ["'majorant'", "'pairs'", "'lowrank'"], 'dsmc:t_end': ['1e-9', '1e-3', '0.1', '10', '100'],
        'dsmc:collisions_per_particle': ['1e-6', '0.01', '1', '5', '20'], 'dsmc:replicas': ['1', '2', '4', '5'],
        'dsmc:seed': ['0', '-1', '1', '9223372036854775807', '18446744073709551615'],
        'dsmc:step_fraction': ['1e-3', '0.1', '1', '10', '1000', '1e-9'], 'dsmc:block_size': ['0', '64', '100', '1000', '2000'],
        'dsmc:stage_step': ['1e-3', '0.125', '10', '1e3'], 'dsmc:allow_long_run': ['.true.'],
        'dsmc:n_particles': ['2', '3', '10', '64', '100', '129', '500', '4000'],
        'output:n_samples': ['1', '2', '3', '500', '1000'], 'output:spacing': ["'log'", "'linear'"],
        'output:first_sample': ['1e-9', '0.5', '1e3', '1e300'], 'output:histogram_bins': ['1', '2', '1000'],
        'output:reduced_bins': ['1', '2', '1000'], 'output:reduced_range': ['0.01', '1', '100'],
        'output:scaling_start': ['0', '0.5', '1e300', '1'], 'output:track_displacements': ['.true.'],
        'output:msd_start_time': ['0', '1', '1e9'], 'output:msd_start_temperature': ['0.5', '1e-9', '2'],
        'output:histogram_range': ['0.01', '1', '100'], 'output:sample_times': ['0.5, 1.0', '1e-9', '1, 1', '2, 1'],
        'output:snapshot_times': ['0', '0.5', '0, 1', '1, 2'], 'output:author': ["'Zoe \\ x'", "''"],
        'output:checkpoint_every': ['0.01', '0'],
        'thermostat:kind': ["'gaussian'", "'white_noise'"], 'thermostat:noise_strength': ['1e-9', '0.001', '1', '1e6'],
        'shear:rate': ['0', '1e-9', '0.003', '0.1', '10'], 'shear:average_from': ['0', '1', '1e9'],
        'agg_frag:aggregation_energy': ['0', '0.5', '1e9'], 'agg_frag:fragmentation_energy': ['0', '1.5', '1e9'],
        'agg_frag:fragment_restitution': ['0', '0.5', '1'],
    }

    def sem_set(self):
        r = self.r
        k = r.choice(list(self.SEM))
        return '%s=%s' % (k, r.choice(self.SEM[k]))

    def rand_path(self, case, purpose, inp, defout):
        """Return (path argument, description) and plant whatever the path needs."""
        r = self.r
        kinds = ['plain', 'space', 'unicode', 'newline', 'long250', 'long300', 'nodir', 'dir', 'dirslash',
                 'text', 'input', 'symlink_text', 'symlink_dangling', 'symlink_dir', 'symlink_out', 'nulldev',
                 'devnull', 'fifo', 'fifo_reader', 'empty', 'dot', 'noext', 'prev', 'corrupt', 'dash', 'colon',
                 'ckptname', 'lockname', 'abs', 'tmpname', 'selfdir', 'nosuchdir_abs', 'default']
        kind = r.choice(kinds)
        if kind.startswith('symlink') or kind in ('nulldev',):
            nm = {'symlink_text': 'link', 'symlink_dangling': 'dang', 'symlink_dir': 'dlink', 'symlink_out': 'olink',
                  'nulldev': 'nulldev'}[kind]
            if any(os.path.lexists(os.path.join(case, nm + e)) for e in ('', '.h5', '.json')):
                kind = 'plain'
        ext = '.json' if purpose == 'json' else '.h5'
        P = lambda *a: os.path.join(case, *a)
        name = 'out' + ext
        if kind == 'space': name = 'with space' + ext
        elif kind == 'unicode': name = 'ünïcødé_жж_✓' + ext
        elif kind == 'newline': name = 'new\nline' + ext
        elif kind == 'long250': name = 'L' * (255 - len(ext)) + ext
        elif kind == 'long300': name = 'L' * 300 + ext
        elif kind == 'nodir': name = 'nodir/sub/out' + ext
        elif kind == 'dir': os.makedirs(P('adir'), exist_ok=True); name = 'adir'
        elif kind == 'dirslash': os.makedirs(P('adir'), exist_ok=True); name = 'adir/'
        elif kind == 'text':
            name = 'existing' + ext; open(P(name), 'w').write('precious user data\n')
        elif kind == 'input': name = inp
        elif kind == 'symlink_text':
            open(P('target.txt'), 'w').write('precious target\n'); os.symlink('target.txt', P('link' + ext)); name = 'link' + ext
        elif kind == 'symlink_dangling': os.symlink('nowhere/x' + ext, P('dang' + ext)); name = 'dang' + ext
        elif kind == 'symlink_dir':
            os.makedirs(P('adir'), exist_ok=True); os.symlink('adir', P('dlink' + ext)); name = 'dlink' + ext
        elif kind == 'symlink_out':
            shutil.copy(os.path.join(self.pool, 'plain.h5'), P('prev_target.h5'))
            os.symlink('prev_target.h5', P('olink' + ext)); name = 'olink' + ext
        elif kind == 'nulldev':
            os.mknod(P('nulldev'), 0o666 | stat.S_IFCHR, os.makedev(1, 3)); name = 'nulldev'
        elif kind == 'devnull': name = '/dev/null'
        elif kind in ('fifo', 'fifo_reader'):
            name = 'fifo' + ext
            if not os.path.exists(P(name)): os.mkfifo(P(name))
        elif kind == 'empty': name = ''
        elif kind == 'dot': name = r.choice(['.', '..', './'])
        elif kind == 'noext': name = 'out'
        elif kind == 'prev':
            name = 'prev' + ext; shutil.copy(os.path.join(self.pool, r.choice(['plain.h5', 'sweep.h5'])), P(name))
        elif kind == 'corrupt':
            name = 'corrupt' + ext; shutil.copy(os.path.join(self.pool, r.choice(['trunc.h5', 'flip.h5', 'foreign.h5'])), P(name))
        elif kind == 'dash': name = r.choice(['-', '--quiet', '-o', '--force'])
        elif kind == 'colon': name = 'a:b=c' + ext
        elif kind == 'ckptname': name = 'out.checkpoint.h5'
        elif kind == 'lockname': name = 'out.lock'
        elif kind == 'abs': name = P('abs' + ext)
        elif kind == 'tmpname': name = 'out.h5.tmp.1'
        elif kind == 'selfdir': name = case
        elif kind == 'nosuchdir_abs': name = '/nonexistent_fuzz33/x' + ext
        elif kind == 'default': name = defout or 'out.h5'
        return name, kind

    # ---------------------------------------------------------------- running
    def snapshot(self, case):
        snap = {}
        for dp, dns, fns in os.walk(case):
            for f in dns + fns:
                p = os.path.join(dp, f)
                try: st = os.lstat(p)
                except FileNotFoundError: continue
                if stat.S_ISREG(st.st_mode):
                    snap[p] = ('f', hashlib.md5(open(p, 'rb').read()).hexdigest())
                elif stat.S_ISLNK(st.st_mode): snap[p] = ('l', os.readlink(p))
                elif stat.S_ISDIR(st.st_mode): snap[p] = ('d', None)
                elif stat.S_ISFIFO(st.st_mode): snap[p] = ('p', None)
                elif stat.S_ISCHR(st.st_mode): snap[p] = ('c', st.st_rdev)
                else: snap[p] = ('?', None)
        return snap

    def execute(self, argv, case, sigint_after=None, devnull=False, stdin_data=None, fifo_in=None, fifo_read=None,
                env_extra=None):
        env = dict(os.environ)
        env['OMP_NUM_THREADS'] = self.r.choice(['1', '1', '2'])
        env['HOME'] = case
        if env_extra: env.update(env_extra)
        full = ['nice', '-n', '19'] + argv
        status_file = os.path.join(case, '.devstatus')
        if devnull:
            script = ('mount -t tmpfs tmpfs /dev && mknod -m 666 /dev/null c 1 3 || exit 99; '
                      '"$@"; rc=$?; { [ -c /dev/null ] && echo chr || echo REPLACED; ls -la /dev; } > %s; exit $rc'
                      % shlex_quote(status_file))
            full = ['unshare', '-m', '--propagation', 'private', 'sh', '-c', script, 'sh'] + full
        t0 = time.time()
        threads = []
        fifo_data = {}
        def writer(path, data):
            try:
                fd = os.open(path, os.O_WRONLY)
                os.write(fd, data); os.close(fd)
            except Exception as e: fifo_data['werr'] = str(e)
        def reader(path):
            try:
                fd = os.open(path, os.O_RDONLY); chunks = []
                while True:
                    c = os.read(fd, 65536)
                    if not c: break
                    chunks.append(c)
                os.close(fd); fifo_data['read'] = b''.join(chunks)
            except Exception as e: fifo_data['rerr'] = str(e)
        for path, data in (fifo_in or []):
            th = threading.Thread(target=writer, args=(path, data), daemon=True); th.start(); threads.append(th)
        for path in (fifo_read or []):
            th = threading.Thread(target=reader, args=(path,), daemon=True); th.start(); threads.append(th)
        p = subprocess.Popen(full, cwd=case, stdin=subprocess.PIPE if stdin_data is not None else subprocess.DEVNULL,
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env, start_new_session=True,
                             preexec_fn=limits)
        timed_out = False; interrupted = False; int_rc = None
        if sigint_after is not None:
            try:
                out, err = p.communicate(input=stdin_data, timeout=sigint_after)
            except subprocess.TimeoutExpired:
                interrupted = True
                try: os.kill(p.pid, signal.SIGINT) if not devnull else os.killpg(p.pid, signal.SIGINT)
                except ProcessLookupError: pass
                try: out, err = p.communicate(timeout=TIMEOUT)
                except subprocess.TimeoutExpired:
                    timed_out = True; os.killpg(p.pid, signal.SIGKILL); out, err = p.communicate()
        else:
            try:
                out, err = p.communicate(input=stdin_data, timeout=TIMEOUT)
            except subprocess.TimeoutExpired:
                timed_out = True
                try: os.killpg(p.pid, signal.SIGINT)
                except ProcessLookupError: pass
                try:
                    out, err = p.communicate(timeout=5); int_rc = p.returncode
                except subprocess.TimeoutExpired:
                    os.killpg(p.pid, signal.SIGKILL); out, err = p.communicate()
        # unblock fifo threads still waiting
        for path, _ in (fifo_in or []):
            try:
                fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK); os.close(fd)
            except Exception: pass
        for path in (fifo_read or []):
            try:
                fd = os.open(path, os.O_WRONLY | os.O_NONBLOCK); os.close(fd)
            except Exception: pass
        for th in threads: th.join(2)
        devstatus = None
        if devnull and os.path.exists(status_file):
            devstatus = open(status_file).read(); os.unlink(status_file)
        return dict(rc=p.returncode, out=out, err=err, dt=time.time() - t0, timed_out=timed_out,
                    interrupted=interrupted, int_rc=int_rc, devstatus=devstatus, fifo=fifo_data)

    # ---------------------------------------------------------------- findings
    def norm(self, s, case):
        s = s.replace(case, 'CASE')
        s = re.sub(r"'[^']*'", "'Q'", s); s = re.sub(r'"[^"]*"', '"Q"', s)
        s = re.sub(r'`[^`]*`', '`Q`', s)
        s = re.sub(r'[-+]?\d+(\.\d*)?([eEdD][-+]?\d+)?', 'N', s)
        s = re.sub(r'L{20,}', 'LONG', s)
        return s[:160]

    def finding(self, kind, severity, argv, res, detail, case, keymsg=None, files=None):
        key = kind + '|' + (keymsg if keymsg is not None else self.norm(detail, case))
        self.stats.setdefault('findings_raw', 0); self.stats['findings_raw'] += 1
        self.case_has_finding = True
        if key in self.seen:
            self.seen[key] += 1; return
        self.seen[key] = 1
        rec = dict(key=key, kind=kind, severity=severity, case=case, argv=argv,
                   rc=res.get('rc') if res else None, stderr=(res['err'].decode(errors='replace')[-3000:] if res else ''),
                   stdout=(res['out'].decode(errors='replace')[-1000:] if res else ''), detail=detail, files=files)
        with open(self.findings_path, 'a') as f: f.write(json.dumps(rec) + '\n')
        print('FINDING', kind, detail[:200].replace('\n', '\\n'), file=sys.stderr)

    def log_msg(self, prog, rc, line, case, argv):
        key = '%s|%s|%s' % (prog, rc, self.norm(line, case))
        if key in self.msgs: return
        self.msgs[key] = 1
        with open(self.msgs_path, 'a') as f:
            f.write(json.dumps(dict(key=key, line=line[:600], argv=argv, case=case)) + '\n')

    def check_common(self, prog, argv, res, case, expect_sigint=False):
        err = res['err'].decode(errors='replace'); out = res['out'].decode(errors='replace')
        rc = res['rc']
        name = os.path.basename(prog)
        if res['timed_out']:
            self.finding('hang', 1, argv, res, 'timeout %ds (SIGINT then rc=%s)' % (TIMEOUT, res['int_rc']), case,
                         keymsg=name + ' ' + ' '.join(a for a in argv[1:] if a.startswith('--') and '=' not in a))
            return
        if rc is not None and rc < 0:
            self.finding('crash', 1, argv, res, 'signal %d; stderr: %s' % (-rc, err[-300:]), case)
            return
        for pat in EXC_PATTERNS:
            if pat in err or pat in out:
                self.finding('exception-text', 2, argv, res, 'pattern %r: %s' % (pat, (err + out)[-300:]), case,
                             keymsg=pat + '|' + self.norm([l for l in (err + out).splitlines() if pat in l][0], case))
                break
        if 'please report' in err:
            self.finding('self-reported-bug', 2, argv, res, [l for l in err.splitlines() if 'please report' in l][0][:300],
                         case, keymsg=self.norm([l for l in err.splitlines() if 'please report' in l][0][:80], case))
        if res['interrupted']:
            if rc not in (130, 0, 1, 2):
                self.finding('sigint-status', 2, argv, res, 'after SIGINT rc=%s: %s' % (rc, err[-300:]), case)
            elif rc != 130:
                self.stats['sigint_but_rc_%s' % rc] = self.stats.get('sigint_but_rc_%s' % rc, 0) + 1
            if rc == 130:
                lines = [l for l in err.split('\n') if l.strip() and not l.startswith(name + ': warning')]
                if len(lines) > 1 or (lines and not lines[0].startswith(name + ': ')):
                    self.finding('multiline-error', 3, argv, res, 'rc 130 stderr %d lines: %s' % (len(lines), err[-300:]),
                                 case, keymsg='sigint|%d' % min(len(lines), 3))
            return
        if rc not in (0, 1, 2):
            self.finding('bad-exit-status', 2, argv, res, 'rc=%s: %s' % (rc, err[-300:]), case)
            return
        if rc in (1, 2):
            lines = err.split('\n')
            if lines and lines[-1] == '': lines = lines[:-1]
            if not lines:
                self.finding('silent-error', 2, argv, res, 'rc=%d with empty stderr' % rc, case, keymsg='rc%d' % rc)
                return
            last = lines[-1]
            self.log_msg(name, rc, lines[0] if 'usage:' in err else last, case, argv)
            if len(lines) != 1 and 'usage:' in err:
                self.finding('usage-dump', 3, argv, res, 'rc=%d, %d stderr lines (usage text after: %s)' % (
                    rc, len(lines), lines[0][:200]), case, keymsg=name)
            elif len(lines) != 1:
                warn = all(l.startswith(name + ': warning') for l in lines[:-1])
                nl_in_arg = any('\n' in a for a in argv)
                kind = 'multiline-error(newline-in-arg)' if nl_in_arg else (
                    'warning-plus-error' if warn else 'multiline-error')
                self.finding(kind, 3, argv, res, 'rc=%d, %d stderr lines: %s' % (rc, len(lines), err[-600:]), case,
                             keymsg=self.norm(lines[0][:60], case) + '|' + self.norm(last[:80], case))
            elif not last.startswith(name + ': '):
                self.finding('error-without-prefix', 3, argv, res, 'rc=%d: %s' % (rc, last[:300]), case)
            if len(last) > 2000:
                self.finding('unclear-message', 4, argv, res, 'error line of %d chars' % len(last), case,
                             keymsg='long-line')
            if re.search(r'\b(nan|inf)\b', last) and 'nan' not in ' '.join(argv).lower():
                pass

    def check_leftovers(self, argv, res, case, before, planted_ok=()):
        after = self.snapshot(case)
        for p in after:
            b = os.path.basename(p)
            if p in before: continue
            named = any(x == b or x.endswith('=' + b) or x.endswith('/' + b) for x in argv)
            if re.search(r'\.tmp\.\d+', b) and not res['timed_out'] and not named:
                self.finding('leftover-tmp', 2, argv, res, 'left %s' % p.replace(case, 'CASE'), case,
                             keymsg=self.norm(b, case))
            if b.endswith('.lock') and not res['timed_out'] and not named:
                self.finding('leftover-lock', 2, argv, res, 'left %s' % p.replace(case, 'CASE'), case,
                             keymsg='lock|rc%s|int%s' % (res['rc'], res['interrupted']))
            if '.kept-' in b:
                self.finding('kept-file', 3, argv, res, 'kept %s' % b, case, keymsg='kept')
        return after

    def check_h5(self, path, argv, res, case):
        import h5py, numpy as np
        try:
            f = h5py.File(path, 'r')
        except Exception as e:
            self.finding('h5-unreadable', 1, argv, res, 'cannot open %s: %s' % (os.path.basename(path), e), case,
                         keymsg='unreadable')
            return
        bad = []
        def visit(name, obj):
            if isinstance(obj, h5py.Dataset) and 'observables' in name.split('/'):
                if obj.dtype.kind == 'f':
                    a = obj[()]
                    if not np.all(np.isfinite(a)):
                        bad.append(name)
        try:
            f.visititems(visit)
        except Exception as e:
            self.finding('h5-unreadable', 1, argv, res, 'visit %s: %s' % (os.path.basename(path), e), case, keymsg='visit')
        f.close()
        for b in bad:
            gen = re.sub(r'point_\d+', 'point_K', b)
            self.finding('nan-in-h5', 1, argv, res, 'non-finite values in %s of %s' % (b, os.path.basename(path)), case,
                         keymsg=gen)

    def check_csv(self, text, argv, res, case):
        rows = list(csv.reader(io.StringIO(text)))
        if not rows: return
        hdr = rows[0]
        for row in rows[1:]:
            if len(row) != len(hdr):
                self.finding('csv-ragged', 2, argv, res, 'row of %d cells, header %d' % (len(row), len(hdr)), case,
                             keymsg='ragged|' + ','.join(hdr[:3]))
                break
            for h, c in zip(hdr, row):
                if c.strip().lower() in ('nan', 'inf', '-inf', '+inf', '-nan') and not h.endswith('_error'):
                    self.finding('nan-in-csv', 1, argv, res, 'column %s = %s' % (h, c), case,
                                 keymsg=re.sub(r'_\d+', '_k', h))
                    return

    def check_json(self, text, argv, res, case, what):
        def bad_const(c): raise ValueError('non-standard constant %s' % c)
        try:
            json.loads(text, parse_constant=bad_const)
        except Exception as e:
            self.finding('json-invalid', 1, argv, res, '%s: %s' % (what, e), case,
                         keymsg=what + '|' + self.norm(str(e), case)[:60])

    def check_dataloss(self, argv, res, case, before, after, planted, force, outpaths):
        for p, (kind, h) in before.items():
            if planted.get(p) in ('output', 'lock', 'checkpoint_own'):  # an earlier output: may be overwritten
                continue
            a = after.get(p)
            if a == (kind, h): continue
            # changed or removed
            rel = p.replace(case, 'CASE')
            tag = planted.get(p, 'unplanted')
            if force and (os.path.abspath(p) in outpaths):
                if tag == 'input':
                    self.finding('force-overwrote-input', 4, argv, res, '--force replaced the input %s' % rel, case,
                                 keymsg='input')
                continue
            self.finding('data-loss', 1, argv, res, '%s %s (%s) %s; force=%s rc=%s' % (
                'removed' if a is None else 'changed', rel, tag, kind, force, res['rc']), case,
                keymsg='%s|%s|%s|force=%s' % (tag, kind, 'removed' if a is None else 'changed', force))

    # ---------------------------------------------------------------- case kinds
    def new_case(self):
        self.ncase += 1
        case = os.path.join(self.cases_dir, '%06d' % self.ncase)
        if os.path.exists(case): shutil.rmtree(case)
        os.makedirs(case)
        self.case_has_finding = False
        return case

    def end_case(self, case, kind, argv, res):
        rc = res['rc'] if res else None
        tag = 'timeout' if res and res['timed_out'] else ('sigint:%s' % rc if res and res['interrupted'] else rc)
        k = '%s:%s' % (kind, tag)
        self.stats[k] = self.stats.get(k, 0) + 1
        self.cases_log.write(json.dumps(dict(n=self.ncase, kind=kind, argv=argv, rc=rc, tag=str(tag),
                                             err=res['err'].decode(errors='replace')[-200:] if res else None,
                                             dt=round(res['dt'], 3) if res else None,
                                             finding=self.case_has_finding)) + '\n')
        self.cases_log.flush()
        if not self.case_has_finding and not self.keep:
            shutil.rmtree(case, ignore_errors=True)

    def case_run(self):
        r = self.r
        case = self.new_case()
        base_name = r.choice(list(self.bases))
        text = self.small(self.bases[base_name], base_name) if r.random() < 0.9 else self.bases[base_name]
        chaos = r.random() < 0.5
        if chaos: text = self.mutate_nml(text, case)
        inp = r.choice(['in.nml'] * 8 + ['my input.nml', 'ïn.nml', 'in', 'in.NML', '-in.nml'])
        planted = {}
        fifo_in = None; stdin_data = None
        inp_kind = r.random()
        if inp_kind < 0.03:
            os.mkfifo(os.path.join(case, inp)); fifo_in = [(os.path.join(case, inp), text.encode('utf-8', 'surrogateescape'))]
            planted[os.path.join(case, inp)] = 'input'
        elif inp_kind < 0.05:
            inp_arg = '/dev/stdin'; stdin_data = text.encode('utf-8', 'surrogateescape')
        else:
            with open(os.path.join(case, inp), 'w', encoding='utf-8', errors='surrogateescape') as f: f.write(text)
            planted[os.path.join(case, inp)] = 'input'
        inp_arg = '/dev/stdin' if stdin_data is not None else inp
        if r.random() < 0.02: inp_arg = r.choice(['nonexistent.nml', '', '.', 'adir'])
        if inp_arg == 'adir': os.makedirs(os.path.join(case, 'adir'), exist_ok=True)
        m = re.search(r"&output[^/]*?file\s*=\s*'([^'\n]*)'", text, re.S | re.I)
        defout = m.group(1) if m else 'run.h5'
        opts = []; force = False; devnull = False; fifo_read = []; json_paths = []
        outpath = None
        if r.random() < 0.85:
            opts += ['--set', 'dsmc:n_particles=%d' % r.choice([500, 1000, 2000, 2000, 3000])]
        if r.random() < 0.5:
            opts += ['--quiet']
        for _ in range(r.choice([0, 0, 1, 1, 2, 3])):
            opts += ['--set', self.sem_set()]
        n_opts = r.choice([0, 0, 1, 1, 2, 2, 3, 4, 6]) if chaos else r.choice([0, 1, 1, 2])
        for _ in range(n_opts):
            k = r.random()
            if k < 0.2:
                opts += ['--set', self.sem_set()]; continue
            k = r.random()
            if k < 0.22:
                name, pk = self.rand_path(case, 'h5', inp, defout)
                if pk == 'devnull': devnull = True
                if pk == 'fifo_reader': fifo_read.append(os.path.join(case, name))
                form = r.random()
                if form < 0.1: opts += ['--output=' + name]
                elif form < 0.13: opts += ['--output']
                else: opts += ['--output', name]
                outpath = name
            elif k < 0.45:
                s = self.rand_set() if chaos else self.sem_set()
                opts += ['--set=' + s] if r.random() < 0.05 else ['--set', s]
            elif k < 0.55:
                if r.random() < 0.5: opts += ['--compare']
                else:
                    name, pk = self.rand_path(case, 'json', inp, None)
                    if pk == 'devnull': devnull = True
                    if pk == 'fifo_reader': fifo_read.append(os.path.join(case, name))
                    opts += ['--compare=' + name]; json_paths.append(name)
            elif k < 0.63:
                src = r.choice(self.pool_files() + ['missing.h5', 'in.nml', '', 'ckpt.checkpoint.h5'])
                if os.path.exists(os.path.join(self.pool, src)) and src.endswith('.h5'):
                    shutil.copy(os.path.join(self.pool, src), os.path.join(case, src))
                    planted[os.path.join(case, src)] = 'restartfile'
                if r.random() < 0.15:
                    name, pk = self.rand_path(case, 'h5', inp, defout); src = name
                    if pk == 'devnull': devnull = True
                opts += ['--restart', src] if r.random() > 0.05 else ['--restart']
            elif k < 0.72: opts += ['--force']; force = True
            elif k < 0.76: opts += ['--quiet']
            elif k < 0.90:
                if not chaos: continue
                opts += r.choice([['--foo'], ['-x'], ['--outputs', 'x.h5'], ['--Quiet'], ['-'], ['--'], ['--table'],
                                  ['--print-defaults'], ['--print-observables'], ['--help'], ['-h'], ['--version'],
                                  ['second.nml'], ['--point', '1'], ['--theory'], ['--set'], ['--compare=', 'x'],
                                  ['--force=yes'], ['--quiet=1'], [''], ['--set', ''], ['--restart='],
                                  ['--output', 'a.h5', '--output', 'b.h5'], ['--OUTPUT', 'x.h5'], ['-o', 'x.h5'],
                                  ['--set', 'dsmc:n_particles=2000', '--set', 'dsmc:n_particles=3000']])
            else:
                # plant something at the default output path / checkpoint / lock
                stem = (outpath or defout)
                stem = stem[:-3] if stem.endswith('.h5') else stem
                what = r.choice(['text_out', 'prev_out', 'text_ckpt', 'pool_ckpt', 'lock', 'dir_out', 'fifo_out'])
                try:
                    tgt = os.path.join(case, outpath or defout)
                    if what == 'text_out':
                        open(tgt, 'w').write('precious\n'); planted[tgt] = 'text'
                    elif what == 'prev_out':
                        shutil.copy(os.path.join(self.pool, 'plain.h5'), tgt); planted[tgt] = 'output'
                    elif what == 'dir_out': os.makedirs(tgt, exist_ok=True)
                    elif what == 'fifo_out': os.mkfifo(tgt)
                    elif what == 'text_ckpt':
                        t = os.path.join(case, stem + '.checkpoint.h5'); open(t, 'w').write('precious ckpt\n'); planted[t] = 'text'
                    elif what == 'pool_ckpt':
                        t = os.path.join(case, stem + '.checkpoint.h5')
                        shutil.copy(os.path.join(self.pool, 'ckpt.checkpoint.h5'), t); planted[t] = 'foreign_ckpt'
                    elif what == 'lock':
                        t = os.path.join(case, stem + '.lock'); open(t, 'w').write(r.choice(['', '1\n', '999999\n', 'junk']))
                        planted[t] = 'lock'
                except Exception:
                    pass
        if r.random() < 0.3:
            # shuffle option groups a little: move the input to the end
            argv = [DSMC] + opts + [inp_arg]
        else:
            argv = [DSMC, inp_arg] + opts
        for p in list(planted):
            if not os.path.lexists(p): del planted[p]
        before = self.snapshot(case)
        for p in before:
            if p not in planted and before[p][0] == 'f':
                planted[p] = 'text' if os.path.basename(p) in ('existing.h5', 'existing.json', 'target.txt') else \
                    ('output' if os.path.basename(p) in ('prev.h5', 'prev_target.h5') else planted.get(p, 'other'))
        sigint = None
        if r.random() < 0.08:
            sigint = r.uniform(0.02, 0.6)
        res = self.execute(argv, case, sigint_after=sigint, devnull=devnull, stdin_data=stdin_data,
                           fifo_in=fifo_in, fifo_read=fifo_read)
        self.check_common(DSMC, argv, res, case)
        if res['devstatus'] is not None and 'REPLACED' in res['devstatus']:
            self.finding('devnull-replaced', 1, argv, res, '/dev/null replaced: ' + res['devstatus'][:300], case,
                         keymsg='devnull')
        if res['devstatus'] is not None and '.tmp.' in res['devstatus']:
            self.finding('leftover-tmp', 2, argv, res, '/dev/null.tmp left: ' + res['devstatus'][:300], case,
                         keymsg='devnull-tmp')
        after = self.check_leftovers(argv, res, case, before)
        outpaths = set()
        for i, a in enumerate(argv):
            if a == '--output' and i + 1 < len(argv): outpaths.add(os.path.abspath(os.path.join(case, argv[i + 1])))
            if a.startswith('--output='): outpaths.add(os.path.abspath(os.path.join(case, a[9:])))
            if a.startswith('--compare='): outpaths.add(os.path.abspath(os.path.join(case, a[10:])))
        if not any(a == '--output' or a.startswith('--output=') for a in argv):
            outpaths.add(os.path.abspath(os.path.join(case, defout)))
        for o in list(outpaths):
            st = o[:-3] if o.endswith('.h5') else o
            outpaths.add(st + '.checkpoint.h5')
            if os.path.islink(o): outpaths.add(os.path.abspath(os.path.join(os.path.dirname(o), os.readlink(o))))
        if not res['timed_out']:
            self.check_dataloss(argv, res, case, before, after, planted, force, outpaths)
        if res['rc'] == 0 and not res['interrupted'] and not res['timed_out']:
            new_h5 = [p for p, v in after.items() if v[0] == 'f' and (before.get(p) != v) and
                      open(p, 'rb').read(8) == b'\x89HDF\r\n\x1a\n']
            run_mode = not any(a in ('--help', '-h', '--version', '--print-defaults', '--print-observables', '--table')
                               for a in argv)
            if run_mode and not new_h5 and not devnull and not any('nulldev' in a for a in argv):
                self.stats['rc0_no_new_h5'] = self.stats.get('rc0_no_new_h5', 0) + 1
            for p in new_h5:
                self.check_h5(p, argv, res, case)
            for jp in (json_paths if run_mode else []):
                full = os.path.join(case, jp)
                if full in fifo_read:
                    data = res['fifo'].get('read')
                    if data is not None: self.check_json(data.decode(errors='replace'), argv, res, case, 'compare-json(fifo)')
                    continue
                if os.path.isfile(full) and not os.path.islink(full) or (os.path.islink(full) and os.path.isfile(full)):
                    self.check_json(open(full, errors='replace').read(), argv, res, case, 'compare-json')
                elif jp and run_mode and '--compare=' + jp in argv and jp not in ('/dev/null', 'nulldev'):
                    self.finding('json-missing', 2, argv, res, 'rc 0 but %s not a file' % jp, case,
                                 keymsg=self.norm(jp, case))
            # follow-up: --table on what was written
            if new_h5 and r.random() < 0.5:
                self.table_on(case, r.choice(new_h5))
        self.end_case(case, 'run', argv, res)

    def table_args(self):
        r = self.r
        q = []
        for _ in range(r.choice([0, 0, 1, 1, 2, 3])):
            k = r.random()
            if k < 0.6: q.append(r.choice(self.observables))
            elif k < 0.75: q.append(r.choice(['summary', 'reduced_distribution', 'temperature_1', 'temperature_2',
                                              'number_10', 'pressure_tensor_xy', 'collisions_pair_1_2',
                                              'temperature_0', 'temperature_999', 'time', 'time_error']))
            elif k < 0.85: q.append(misspell(r, r.choice(self.observables)))
            else: q.append(r.choice(['', '-', '--foo', 'summary,temperature', 'TEMPERATURE', 'temperature ']))
        if r.random() < 0.3: q += ['--point', r.choice(['1', '2', '0', '-1', '7', '99999999999999999999', 'x', '1.5', ''])]
        if r.random() < 0.05: q += ['--point']
        if r.random() < 0.3: q += ['--theory']
        if r.random() < 0.05: q += r.choice([['--quiet'], ['--output', 'x.h5'], ['--force'], ['--set', 'dsmc:seed=1'],
                                             ['--table', 'plain.h5'], ['--theory']])
        return q

    def table_on(self, case, path):
        argv = [DSMC, '--table', os.path.relpath(path, case)] + self.table_args()
        before = self.snapshot(case)
        res = self.execute(argv, case)
        self.check_common(DSMC, argv, res, case)
        self.check_leftovers(argv, res, case, before)
        if res['rc'] == 0 and not res['timed_out']:
            self.check_csv(res['out'].decode(errors='replace'), argv, res, case)
        if self.check_dataloss(argv, res, case, before, self.snapshot(case), {}, False, set()): pass
        self.end_case_inner('table-followup', res)

    def end_case_inner(self, kind, res):
        tag = 'timeout' if res['timed_out'] else res['rc']
        k = '%s:%s' % (kind, tag); self.stats[k] = self.stats.get(k, 0) + 1

    def case_table(self):
        r = self.r
        case = self.new_case()
        src = r.choice(self.pool_files() + ['missing.h5', 'ckpt.nml'])
        if os.path.exists(os.path.join(self.pool, src)):
            shutil.copy(os.path.join(self.pool, src), os.path.join(case, src))
        if r.random() < 0.15:
            src, pk = self.rand_path(case, 'h5', 'in.nml', None)
        args = self.table_args()
        argv = [DSMC, '--table', src] + args if r.random() > 0.03 else [DSMC, '--table']
        if r.random() < 0.1: argv = [DSMC] + args + ['--table', src]
        before = self.snapshot(case)
        res = self.execute(argv, case, devnull=(src == '/dev/null'),
                           fifo_in=[(os.path.join(case, src), b'junk')] if src.startswith('fifo') and r.random() < 0.5 else None)
        self.check_common(DSMC, argv, res, case)
        self.check_leftovers(argv, res, case, before)
        self.check_dataloss(argv, res, case, before, self.snapshot(case), {}, False, set())
        if res['rc'] == 0 and not res['timed_out'] and src != 'nantime.h5':
            self.check_csv(res['out'].decode(errors='replace'), argv, res, case)
        self.end_case(case, 'table', argv, res)

    def case_theory(self):
        r = self.r
        case = self.new_case()
        base_name = r.choice(list(self.bases))
        text = self.mutate_nml(self.small(self.bases[base_name], base_name), case)
        open(os.path.join(case, 'in.nml'), 'w', encoding='utf-8', errors='surrogateescape').write(text)
        argv = [THEORY, 'in.nml']
        for _ in range(r.choice([0, 0, 1, 2, 3])):
            k = r.random()
            if k < 0.35: argv += ['--set', self.rand_set()]
            elif k < 0.7: argv += ['--set', self.sem_set()]
            else: argv += r.choice([['--foo'], ['--set'], ['--quiet'], ['--output', 'x'], ['--help'], ['extra.nml'],
                                    ['--compare'], ['-'], ['--print-defaults'], ['--version']])
        before = self.snapshot(case)
        res = self.execute(argv, case)
        self.check_common(THEORY, argv, res, case)
        self.check_leftovers(argv, res, case, before)
        self.check_dataloss(argv, res, case, before, self.snapshot(case), {}, False, set())
        if res['rc'] == 0 and not res['timed_out'] and not any(a in ('--help', '-h', '--version') for a in argv):
            self.check_json(res['out'].decode(errors='replace'), argv, res, case, 'theory-stdout')
        self.end_case(case, 'theory', argv, res)

    def case_misc(self):
        r = self.r
        case = self.new_case()
        shutil.copy(os.path.join(self.pool, 'plain.nml'), os.path.join(case, 'in.nml'))
        argv = [r.choice([DSMC, THEORY])] + r.choice([
            [], ['--print-defaults'], ['--print-defaults', 'x'], ['--print-defaults', '--print-defaults'],
            ['--print-observables'], ['--help'], ['--version'], ['-h'], ['--'], ['-'], [''], ['--set'],
            ['--set', 'dsmc:seed=1'], ['--table'], ['--output', 'x.h5'], ['in.nml', 'in.nml'],
            ['--print-defaults', 'in.nml'], ['in.nml', '--print-defaults'], ['--quiet'], ['--force'],
            ['--restart', 'x'], ['--compare'], ['in.nml', '--help'], ['--help', 'in.nml'], ['\xff'],
            ['in.nml', '--set', 'dsmc:n_particles=2000', '--set']])
        before = self.snapshot(case)
        res = self.execute(argv, case)
        self.check_common(argv[0], argv, res, case)
        self.check_leftovers(argv, res, case, before)
        self.check_dataloss(argv, res, case, before, self.snapshot(case), {'%s/in.nml' % case: 'input'}, False, set())
        self.end_case(case, 'misc', argv, res)

    def case_roundtrip(self):
        """--print-defaults output is a valid input."""
        r = self.r
        case = self.new_case()
        open(os.path.join(case, 'd.nml'), 'w').write(self.defaults_text)
        argv = [DSMC, 'd.nml', '--quiet', '--set', 'dsmc:n_particles=2000', '--set', 'dsmc:collisions_per_particle=5']
        res = self.execute(argv, case)
        before = {}
        self.check_common(DSMC, argv, res, case)
        if res['rc'] != 0:
            self.finding('defaults-not-runnable', 3, argv, res, res['err'].decode(errors='replace')[-300:], case)
        self.end_case(case, 'roundtrip', argv, res)

    def case_restart(self):
        """interrupt a checkpointing run, then --restart; compare with an uninterrupted run."""
        r = self.r
        case = self.new_case()
        base = r.choice(['sweep.nml', 'haff.nml', 'binary-hcs.nml', 'agg-frag.nml', 'rough-cooling.nml',
                         'msd-binary.nml', 'usf.nml'])
        text = self.bases[base]
        text = re.sub(r'n_particles\s*=\s*\d+', 'n_particles = %d' % r.choice([20000, 40000]), text)
        text = re.sub(r'replicas\s*=\s*\d+', 'replicas = %d' % r.choice([2, 3, 4]), text)
        text = re.sub(r'\s*checkpoint_every\s*=\s*[\d.]+', '', text)
        text = re.sub(r'(&output)', r'\1\n  checkpoint_every = %s' % r.choice(['0.01', '0.05', '0.2']), text, 1)
        A = os.path.join(case, 'A'); B = os.path.join(case, 'B'); os.makedirs(A); os.makedirs(B)
        for d in (A, B): open(os.path.join(d, 'in.nml'), 'w').write(text)
        extra = ['--quiet'] if r.random() < 0.5 else []
        argvA = [DSMC, 'in.nml'] + extra
        resA = self.execute(argvA, A)
        self.check_common(DSMC, argvA, resA, A)
        argvB = [DSMC, 'in.nml'] + extra
        beforeB = self.snapshot(B)
        resB = self.execute(argvB, B, sigint_after=r.uniform(0.2, max(0.3, resA['dt'] * 0.8)))
        self.check_common(DSMC, argvB, resB, B)
        self.check_leftovers(argvB, resB, B, beforeB)
        m = re.search(r"file\s*=\s*'([^']*)'", text); out = m.group(1); stem = out[:-3]
        ck = stem + '.checkpoint.h5'
        res = resB
        if resB['interrupted'] and resB['rc'] == 130 and os.path.exists(os.path.join(B, ck)):
            self.stats['restart_ckpt_made'] = self.stats.get('restart_ckpt_made', 0) + 1
            mode = r.random()
            argvC = [DSMC, 'in.nml', '--restart', ck] + extra
            if mode < 0.15:
                argvC += ['--set', 'dsmc:seed=99']  # another input: must be refused
            before = self.snapshot(B)
            resC = self.execute(argvC, B)
            self.check_common(DSMC, argvC, resC, B)
            self.check_leftovers(argvC, resC, B, before)
            res = resC
            if mode < 0.15:
                if resC['rc'] == 0:
                    self.finding('restart-accepts-other-input', 2, argvC, resC, 'restart with different --set accepted', B,
                                 keymsg='seed')
            elif resC['rc'] != 0:
                self.finding('restart-failed', 2, argvC, resC, 'rc=%s %s' % (resC['rc'], resC['err'].decode(errors='replace')[-300:]),
                             B, keymsg='restart|' + self.norm(resC['err'].decode(errors='replace')[-120:], B))
            elif resA['rc'] == 0:
                diff = self.compare_h5(os.path.join(A, out), os.path.join(B, out))
                if diff:
                    self.finding('restart-differs', 2, argvC, resC, 'restarted output differs from uninterrupted: %s' % diff,
                                 B, keymsg=base + '|' + diff.split(':')[0])
                if os.path.exists(os.path.join(B, ck)):
                    self.finding('checkpoint-left', 3, argvC, resC, 'checkpoint kept after completed restart', B,
                                 keymsg='ck')
        self.end_case(case, 'restart', argvB, res)

    def compare_h5(self, a, b):
        import h5py, numpy as np
        try:
            fa = h5py.File(a, 'r'); fb = h5py.File(b, 'r')
        except Exception as e:
            return 'open: %s' % e
        diffs = []
        def visit(name, obj):
            if isinstance(obj, h5py.Dataset) and ('observables' in name or 'particles' in name):
                if name not in fb: diffs.append('missing: ' + name); return
                x, y = obj[()], fb[name][()]
                try:
                    if not np.array_equal(x, y, equal_nan=True) if x.dtype.kind == 'f' else not np.array_equal(x, y):
                        diffs.append('values: ' + name)
                except Exception:
                    if not np.array_equal(x, y): diffs.append('values: ' + name)
        fa.visititems(visit)
        fa.close(); fb.close()
        return ', '.join(diffs[:5])

    def run(self, minutes):
        t_end = time.time() + minutes * 60
        last = time.time()
        while time.time() < t_end:
            k = self.r.random()
            try:
                if k < 0.62: self.case_run()
                elif k < 0.77: self.case_table()
                elif k < 0.90: self.case_theory()
                elif k < 0.95: self.case_misc()
                elif k < 0.99: self.case_restart()
                else: self.case_roundtrip()
            except Exception as e:
                import traceback
                traceback.print_exc()
                self.stats['fuzzer_error'] = self.stats.get('fuzzer_error', 0) + 1
            if time.time() - last > 30:
                last = time.time(); self.dump_stats()
        self.dump_stats()

    def dump_stats(self):
        st = dict(self.stats); st['cases'] = self.ncase; st['distinct_findings'] = len(self.seen)
        json.dump(st, open(os.path.join(self.root, 'stats.json'), 'w'), indent=1, sort_keys=True)
        print('cases', self.ncase, 'findings', len(self.seen), file=sys.stderr)


def shlex_quote(s):
    import shlex; return shlex.quote(s)


if __name__ == '__main__':
    ap = argparse.ArgumentParser()
    ap.add_argument('--minutes', type=float, default=45)
    ap.add_argument('--seed', type=int, default=int(time.time()))
    ap.add_argument('--root', default='cli-fuzz')
    ap.add_argument('--bin', default='build/bin', help='folder of granular-dsmc and granular-theory')
    ap.add_argument('--keep', action='store_true')
    a = ap.parse_args()
    DSMC = os.path.abspath(os.path.join(a.bin, 'granular-dsmc'))
    THEORY = os.path.abspath(os.path.join(a.bin, 'granular-theory'))
    a.root = os.path.abspath(a.root)
    print('seed', a.seed, file=sys.stderr)
    Fuzzer(a.root, a.seed, a.keep).run(a.minutes)
