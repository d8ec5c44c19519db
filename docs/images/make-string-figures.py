#!/usr/bin/env python3
"""Draw the user guide's two figures comparing the 110 Hz strings.

Writes, into docs/images/:

  string-spectrograms-110.png
      Spectrograms (0-20 kHz, 0-3.5 s, dB relative to the louder of the two
      recordings' peak, -100 ... 0 dB) of the paper's 110 Hz string
      (resources/models/bowed-string-110-paper.json: 60 masses, link damping)
      beside the full-bandwidth one (resources/models/bowed-string-110.json:
      214 masses, sigma0 + sigma1 omega^2 damping, violin body), each played
      with its own embedded bow stroke.  Hann window, 2048 points, hop 512.

  string-t60-110.png
      The 60 dB decay time T60 of every partial (log axis) against its
      frequency, for the same two models, from `archet modes MODEL --json`
      (support / body modes are left out).

Run it from the repository root, giving the archet binary to use:

    python3 docs/images/make-string-figures.py build/bin/archet

It needs only Python 3's standard library and ImageMagick's `convert`
(ImageMagick 6 or 7); it renders into a temporary folder and leaves nothing
else behind.
"""

import cmath
import json
import math
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import time

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
MODELS = os.path.join(REPO, "resources", "models")
OUT_DIR = os.path.join(REPO, "docs", "images")

STRINGS = [
    # (model file, panel title / legend text, curve colour)
    ("bowed-string-110-paper.json", "paper's string: 60 masses, link damping", "#d95f02"),
    ("bowed-string-110.json", "full-bandwidth string: 214 masses, \u03c30+\u03c31\u03c9\u00b2, violin body",
     "#1f5fb4"),
]

DURATION = 3.5          # s, the time axis of the spectrograms
F_MAX = 20000.0         # Hz, top of the spectrograms
N_FFT = 2048
HOP = 512
DB_RANGE = 100.0        # dB below the peak shown in the spectrograms

FONT_CANDIDATES = [
    "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/TTF/DejaVuSans.ttf",
    "/usr/share/fonts/dejavu/DejaVuSans.ttf",
    "/Library/Fonts/DejaVuSans.ttf",
]


# --------------------------------------------------------------------------- input

def read_wav(path):
    """Mono samples (floats, full scale = 1) and sample rate of a PCM or float WAV."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:4] != b"RIFF" or data[8:12] != b"WAVE":
        raise ValueError(path + ": not a RIFF/WAVE file")
    pos, fmt, raw = 12, None, None
    while pos + 8 <= len(data):
        cid, size = data[pos:pos + 4], struct.unpack("<I", data[pos + 4:pos + 8])[0]
        body = data[pos + 8:pos + 8 + size]
        if cid == b"fmt ":
            tag, channels, rate = struct.unpack("<HHI", body[:8])
            bits = struct.unpack("<H", body[14:16])[0]
            if tag == 0xFFFE and len(body) >= 26:       # WAVE_FORMAT_EXTENSIBLE
                tag = struct.unpack("<H", body[24:26])[0]
            fmt = (tag, channels, rate, bits)
        elif cid == b"data":
            raw = body
        pos += 8 + size + (size & 1)
    if fmt is None or raw is None:
        raise ValueError(path + ": no fmt or data chunk")
    tag, channels, rate, bits = fmt
    width = bits // 8
    n = len(raw) // (width * channels)
    if tag == 3 and bits in (32, 64):
        vals = struct.unpack("<%d%s" % (n * channels, "f" if bits == 32 else "d"), raw[:n * channels * width])
    elif tag == 1 and bits == 16:
        vals = [v / 32768.0 for v in struct.unpack("<%dh" % (n * channels), raw[:n * channels * 2])]
    elif tag == 1 and bits == 32:
        vals = [v / 2147483648.0 for v in struct.unpack("<%di" % (n * channels), raw[:n * channels * 4])]
    elif tag == 1 and bits == 24:
        vals = []
        for i in range(0, n * channels * 3, 3):
            v = raw[i] | (raw[i + 1] << 8) | (raw[i + 2] << 16)
            vals.append((v - (1 << 24) if v & 0x800000 else v) / 8388608.0)
    else:
        raise ValueError("%s: unsupported WAV format (tag %d, %d bits)" % (path, tag, bits))
    return list(vals[::channels]), rate


def run(cmd):
    proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True)
    if proc.returncode != 0:
        sys.exit("failed (%d): %s\n%s" % (proc.returncode, " ".join(cmd), proc.stderr))
    return proc.stdout


# --------------------------------------------------------------------------- FFT

def make_fft(n):
    """A radix-2 complex FFT of size n (in place on a list), with tables computed once."""
    bits = n.bit_length() - 1
    rev = [int(format(i, "0%db" % bits)[::-1], 2) for i in range(n)]
    swaps = [(i, j) for i, j in enumerate(rev) if i < j]
    stages = []
    size = 2
    while size <= n:
        half = size // 2
        tw = [cmath.exp(-2j * math.pi * k / size) for k in range(half)]
        stages.append((size, half, tw))
        size *= 2

    def fft(a):
        for i, j in swaps:
            a[i], a[j] = a[j], a[i]
        for size, half, tw in stages:
            for start in range(0, n, size):
                for k in range(half):
                    i = start + k
                    t = tw[k] * a[i + half]
                    u = a[i]
                    a[i] = u + t
                    a[i + half] = u - t
        return a

    return fft


def spectrogram(x, n_fft=N_FFT, hop=HOP):
    """Power spectra (bins 0..n/2) of Hann-windowed frames; two real frames per complex FFT."""
    fft = make_fft(n_fft)
    win = [0.5 - 0.5 * math.cos(2 * math.pi * i / n_fft) for i in range(n_fft)]
    if len(x) < n_fft:
        x = x + [0.0] * (n_fft - len(x))
    starts = list(range(0, len(x) - n_fft + 1, hop))
    half = n_fft // 2
    frames = []
    for p in range(0, len(starts), 2):
        s0 = starts[p]
        s1 = starts[p + 1] if p + 1 < len(starts) else None
        if s1 is None:
            a = [complex(x[s0 + i] * win[i], 0.0) for i in range(n_fft)]
        else:
            a = [complex(x[s0 + i] * win[i], x[s1 + i] * win[i]) for i in range(n_fft)]
        fft(a)
        pa, pb = [], []
        for k in range(half + 1):
            z, zc = a[k], a[-k % n_fft].conjugate()
            xa = 0.5 * (z + zc)              # spectrum of the real part
            xb = -0.5j * (z - zc)            # spectrum of the imaginary part
            pa.append(xa.real * xa.real + xa.imag * xa.imag)
            pb.append(xb.real * xb.real + xb.imag * xb.imag)
        frames.append(pa)
        if s1 is not None:
            frames.append(pb)
    centres = [(s + n_fft / 2) for s in starts]
    return frames, centres


# --------------------------------------------------------------------------- colour

INFERNO = [  # (position, r, g, b): a few stops of matplotlib's "inferno"
    (0.00, 0, 0, 4), (0.13, 31, 12, 72), (0.25, 85, 15, 109), (0.38, 136, 34, 106),
    (0.50, 186, 54, 85), (0.63, 227, 89, 51), (0.75, 249, 140, 10), (0.88, 249, 201, 50),
    (1.00, 252, 255, 164),
]


def colour(u):
    u = min(1.0, max(0.0, u))
    for (p0, *c0), (p1, *c1) in zip(INFERNO, INFERNO[1:]):
        if u <= p1:
            w = (u - p0) / (p1 - p0)
            return bytes(int(round(a + (b - a) * w)) for a, b in zip(c0, c1))
    return bytes(INFERNO[-1][1:])


LUT = [colour(i / 255.0) for i in range(256)]


def write_ppm(path, width, height, rows):
    with open(path, "wb") as f:
        f.write(b"P6\n%d %d\n255\n" % (width, height))
        for row in rows:
            f.write(b"".join(row))


def spectrogram_image(path, frames, centres, rate, ref_power, width, height):
    """Write the plot area of one spectrogram as a PPM: x is time 0..DURATION, y is 0..F_MAX (top)."""
    n_bins = len(frames[0])
    bin_hz = rate / N_FFT
    # for every pixel column, the frame whose centre is nearest its time
    cols = []
    for px in range(width):
        t = (px + 0.5) / width * DURATION * rate
        j = min(range(len(centres)), key=lambda k: abs(centres[k] - t)) if t <= centres[-1] + HOP else None
        cols.append(j)
    # for every pixel row, the bins it covers (strongest bin shown)
    row_bins = []
    for py in range(height):
        f_hi = (height - py) / height * F_MAX
        f_lo = (height - py - 1) / height * F_MAX
        lo = int(math.ceil(f_lo / bin_hz))
        hi = int(math.floor(f_hi / bin_hz))
        if hi < lo:
            lo = hi = int(round(0.5 * (f_lo + f_hi) / bin_hz))
        row_bins.append((max(0, lo), min(n_bins - 1, hi)))
    # dB of every frame, mapped to 0..255
    floor = ref_power * 10 ** (-DB_RANGE / 10)
    levels = []
    for fr in frames:
        levels.append([int(max(0.0, min(255.0, 255.0 * (1.0 + 10 * math.log10(max(p, floor) / ref_power)
                                                      / DB_RANGE)))) for p in fr])
    black = LUT[0]
    rows = []
    for lo, hi in row_bins:
        row = []
        for j in cols:
            if j is None:
                row.append(black)
            else:
                lv = levels[j]
                row.append(LUT[max(lv[lo:hi + 1])])
        rows.append(row)
    write_ppm(path, width, height, rows)


def colourbar_image(path, width, height):
    rows = [[LUT[int(round(255 * (height - 1 - y) / (height - 1)))]] * width for y in range(height)]
    write_ppm(path, width, height, rows)


# --------------------------------------------------------------------------- drawing helpers

class Canvas:
    """Collects ImageMagick drawing operations for one white canvas."""

    def __init__(self, width, height, font):
        self.w, self.h = width, height
        self.ops = []
        self.font = font

    def image(self, path, x, y):
        self.ops += [path, "-geometry", "+%d+%d" % (x, y), "-composite"]

    def draw(self, primitive, stroke="black", fill="none", width=1.0):
        self.ops += ["-stroke", stroke, "-strokewidth", "%g" % width, "-fill", fill, "-draw", primitive]

    def line(self, x0, y0, x1, y1, colour="black", width=1.0):
        self.draw("line %.1f,%.1f %.1f,%.1f" % (x0, y0, x1, y1), stroke=colour, width=width)

    def rect(self, x0, y0, x1, y1, colour="black", fill="none", width=1.0):
        self.draw("rectangle %.1f,%.1f %.1f,%.1f" % (x0, y0, x1, y1), stroke=colour, fill=fill, width=width)

    def polyline(self, pts, colour, width=2.0):
        if len(pts) >= 2:
            self.draw("polyline " + " ".join("%.1f,%.1f" % p for p in pts), stroke=colour, width=width)

    def dot(self, x, y, r, colour):
        self.draw("circle %.1f,%.1f %.1f,%.1f" % (x, y, x + r, y), stroke=colour, fill=colour, width=1)

    def text(self, x, y, s, size=15, anchor="c", colour="black", rotate=0, bold=False):
        """Text centred ('c'), right-aligned ('r') or left-aligned ('l') at x, vertically centred at y."""
        gravity = {"c": "Center", "r": "East", "l": "West"}[anchor]
        if anchor == "c":
            dx = x - self.w / 2.0
        elif anchor == "r":
            dx = self.w - x
        else:
            dx = x
        dy = y - self.h / 2.0
        font = self.font.replace("DejaVuSans.ttf", "DejaVuSans-Bold.ttf") if bold and self.font else self.font
        ops = ["-stroke", "none", "-fill", colour, "-gravity", gravity, "-pointsize", str(size)]
        if font:
            ops += ["-font", font]
        ops += ["-annotate", "%dx%d%+d%+d" % (rotate, rotate, round(dx), round(dy)), s, "-gravity", "NorthWest"]
        self.ops += ops

    def save(self, path):
        cmd = [convert_tool(), "-size", "%dx%d" % (self.w, self.h), "xc:white", "-gravity", "NorthWest"]
        cmd += self.ops + ["-strip", path]
        run(cmd)


def convert_tool():
    if shutil.which("convert"):
        return "convert"
    if shutil.which("magick"):
        return "magick"
    sys.exit("ImageMagick (convert or magick) is needed")


def find_font():
    for p in FONT_CANDIDATES:
        if os.path.exists(p):
            return p
    return None  # ImageMagick's default font


# --------------------------------------------------------------------------- figures

def figure_spectrograms(archet, tmp, font, out):
    W, H = 1400, 600
    PW, PH = 540, 460               # plot area of one panel
    X0 = [80, 720]                  # left edge of each panel
    Y0 = 58                         # top edge of the plot areas
    CB_X, CB_W = 1290, 20           # colour bar
    spectra = []
    for model, _, _ in STRINGS:
        wav = os.path.join(tmp, model.replace(".json", ".wav"))
        run([archet, "render", os.path.join(MODELS, model), "-o", wav, "--duration", "%g" % DURATION])
        x, rate = read_wav(wav)
        frames, centres = spectrogram(x)
        spectra.append((frames, centres, rate))
    ref = max(max(max(fr) for fr in frames) for frames, _, _ in spectra)

    c = Canvas(W, H, font)
    for i, ((frames, centres, rate), (model, title, _)) in enumerate(zip(spectra, STRINGS)):
        ppm = os.path.join(tmp, "panel%d.ppm" % i)
        spectrogram_image(ppm, frames, centres, rate, ref, PW, PH)
        x0 = X0[i]
        c.image(ppm, x0, Y0)
        c.rect(x0 - 0.5, Y0 - 0.5, x0 + PW - 0.5, Y0 + PH - 0.5)
        c.text(x0 + PW / 2, 28, title, size=17)
        for t in [0, 0.5, 1, 1.5, 2, 2.5, 3, 3.5]:
            px = x0 + t / DURATION * (PW - 1)
            c.line(px, Y0 + PH, px, Y0 + PH + 6)
            c.text(px, Y0 + PH + 18, ("%g" % t), size=14)
        c.text(x0 + PW / 2, Y0 + PH + 46, "time (s)", size=16)
        for f in range(0, 21, 2):
            py = Y0 + PH - f * 1000 / F_MAX * (PH - 1) - 1
            c.line(x0 - 6, py, x0, py)
            c.text(x0 - 10, py, "%d" % f, size=14, anchor="r")
        c.text(x0 - 48, Y0 + PH / 2, "frequency (kHz)", size=16, rotate=270)
    cb = os.path.join(tmp, "colourbar.ppm")
    colourbar_image(cb, CB_W, PH)
    c.image(cb, CB_X, Y0)
    c.rect(CB_X - 0.5, Y0 - 0.5, CB_X + CB_W - 0.5, Y0 + PH - 0.5)
    for db in range(0, -int(DB_RANGE) - 1, -20):
        py = Y0 + (-db) / DB_RANGE * (PH - 1)
        c.line(CB_X + CB_W, py, CB_X + CB_W + 5, py)
        c.text(CB_X + CB_W + 9, py, "%d" % db, size=14, anchor="l")
    c.text(CB_X + CB_W + 62, Y0 + PH / 2, "dB re. peak (both recordings)", size=16, rotate=90)
    c.text(W / 2, H - 14, "Hann window 2048 points, hop 512, 48 kHz; each string played with its own embedded bow stroke",
           size=13, colour="#555555")
    c.save(out)


def figure_t60(archet, font, out):
    W, H = 1400, 600
    X0, X1, Y0, Y1 = 100, 1360, 55, 515
    F_TOP = 22000.0                 # the full string's highest partials lie just above 20 kHz
    T_LO, T_HI = 1e-3, 10.0
    curves = []
    for model, label, col in STRINGS:
        data = json.loads(run([archet, "modes", os.path.join(MODELS, model), "--json"]))
        pts = sorted((m["frequency"], m["t60"]) for m in data["modes"]
                     if m.get("kind") != "support" and m.get("partial") is not None
                     and m.get("t60") and m["t60"] > 0 and math.isfinite(m["t60"]))
        curves.append((pts, label, col))

    def X(f):
        return X0 + f / F_TOP * (X1 - X0)

    def Y(t):
        t = min(max(t, T_LO), T_HI)
        return Y1 - (math.log10(t) - math.log10(T_LO)) / (math.log10(T_HI) - math.log10(T_LO)) * (Y1 - Y0)

    c = Canvas(W, H, font)
    # grid
    for f in range(0, int(F_TOP / 1000) + 1, 2):
        c.line(X(f * 1000), Y0, X(f * 1000), Y1, colour="#e4e4e4")
    for e in range(-3, 2):
        for m in range(1, 10):
            t = m * 10.0 ** e
            if T_LO <= t <= T_HI:
                c.line(X0, Y(t), X1, Y(t), colour="#d0d0d0" if m == 1 else "#f0f0f0")
    # curves
    for pts, label, col in curves:
        c.polyline([(X(f), Y(t)) for f, t in pts if f <= F_TOP], col, width=2.0)
        for f, t in pts:
            if f <= F_TOP:
                c.dot(X(f), Y(t), 2.6, col)
    # axes, ticks, labels
    c.rect(X0, Y0, X1, Y1)
    for f in range(0, int(F_TOP / 1000) + 1, 2):
        c.line(X(f * 1000), Y1, X(f * 1000), Y1 + 6)
        c.text(X(f * 1000), Y1 + 18, "%d" % f, size=14)
    c.text((X0 + X1) / 2, Y1 + 46, "partial frequency (kHz)", size=16)
    for e in range(-3, 2):
        t = 10.0 ** e
        c.line(X0 - 7, Y(t), X0, Y(t))
        c.text(X0 - 11, Y(t), {-3: "0.001", -2: "0.01", -1: "0.1", 0: "1", 1: "10"}[e], size=14, anchor="r")
        for m in range(2, 10):
            if m * t <= T_HI:
                c.line(X0 - 4, Y(m * t), X0, Y(m * t))
    c.text(X0 - 62, (Y0 + Y1) / 2, "T60 (s), log scale", size=16, rotate=270)
    c.text((X0 + X1) / 2, 27, "T60 of each partial, 110 Hz strings", size=19, bold=True)
    # legend
    longest = max(len("%s (%d partials)" % (label, len(pts))) for pts, label, _ in curves)
    LX, LY = X1 - 14 - (80 + 8.6 * longest), Y0 + 14   # about 8.6 px a character at 14 pt
    c.rect(LX, LY, X1 - 14, LY + 62, colour="#999999", fill="white")
    for k, (pts, label, col) in enumerate(curves):
        y = LY + 18 + 26 * k
        c.line(LX + 12, y, LX + 52, y, colour=col, width=2.5)
        c.dot(LX + 32, y, 3, col)
        c.text(LX + 62, y, "%s (%d partials)" % (label, len(pts)), size=14, anchor="l")
    c.save(out)
    return curves


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    archet = os.path.abspath(sys.argv[1])
    if not os.access(archet, os.X_OK):
        sys.exit("not an executable: " + sys.argv[1])
    font = find_font()
    os.makedirs(OUT_DIR, exist_ok=True)
    start = time.time()
    with tempfile.TemporaryDirectory() as tmp:
        spec = os.path.join(OUT_DIR, "string-spectrograms-110.png")
        figure_spectrograms(archet, tmp, font, spec)
        print("wrote", os.path.relpath(spec))
    t60 = os.path.join(OUT_DIR, "string-t60-110.png")
    curves = figure_t60(archet, font, t60)
    print("wrote", os.path.relpath(t60))
    for pts, label, _ in curves:
        near = min(pts, key=lambda p: abs(p[0] - 2000))
        print("  %s: %d partials up to %.0f Hz; T60 %.3g s at %.0f Hz" % (label, len(pts), pts[-1][0], near[1], near[0]))
    print("took %.1f s" % (time.time() - start))


if __name__ == "__main__":
    main()
