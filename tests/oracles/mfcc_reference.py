#!/usr/bin/env python3
"""Independent NumPy reference for glossa's MFCC and log-mel encoders (tests/test_mfcc.cpp).

Implements the configuration documented at the top of src/features/mel_encoders.cpp and in
src/features/spectrum.h from the definitions, in float64, without reading glossa's code:

  * frames centred on sample t * hop, the signal zero-padded by n_fft / 2 on both sides,
    ceil(n / hop) frames;
  * periodic Hann window of n_fft samples, w[i] = 0.5 - 0.5 cos(2 pi i / n_fft);
  * power spectrum |rfft|^2;
  * mel filterbank as librosa.filters.mel(htk=False, norm="slaney") documents it: the Slaney
    mel scale (linear, 3 mels per 200 Hz, below 1 kHz; logarithmic above, 27 mels per factor
    6.4), n_mels + 2 points evenly spaced in mel between fmin and fmax, triangles over the FFT
    bin frequencies, each scaled by 2 / (upper edge - lower edge) in Hz (area normalisation);
  * 10 log10(max(mel power, 1e-10));
  * MFCC: orthonormal DCT-II of the log-mel vector (scipy.fft.dct(type=2, norm="ortho")),
    first n_mfcc coefficients.

usage: mfcc_reference.py INPUT.npy OUT_DIR
  INPUT.npy: 1-D float array, 16 kHz audio.
  Writes to OUT_DIR: mfcc.npy [frames, 27] (27 mels), logmel.npy [frames, 40] (40 mels),
  melfb27.npy [27, 257], power.npy [frames, 257], all float64.
"""
import os
import sys

import numpy as np

SR = 16000
N_FFT = 512
HOP = 320


def hz_to_mel(hz):
    hz = np.asarray(hz, dtype=np.float64)
    f_sp = 200.0 / 3.0  # Hz per mel in the linear part
    min_log_hz = 1000.0
    min_log_mel = min_log_hz / f_sp
    logstep = np.log(6.4) / 27.0  # 27 mels per factor 6.4 above 1 kHz
    lin = hz / f_sp
    log = min_log_mel + np.log(np.maximum(hz, min_log_hz) / min_log_hz) / logstep
    return np.where(hz >= min_log_hz, log, lin)


def mel_to_hz(mel):
    mel = np.asarray(mel, dtype=np.float64)
    f_sp = 200.0 / 3.0
    min_log_hz = 1000.0
    min_log_mel = min_log_hz / f_sp
    logstep = np.log(6.4) / 27.0
    lin = mel * f_sp
    log = min_log_hz * np.exp(logstep * (np.maximum(mel, min_log_mel) - min_log_mel))
    return np.where(mel >= min_log_mel, log, lin)


def mel_filterbank(n_mels, fmin=0.0, fmax=SR / 2.0):
    bin_hz = np.arange(N_FFT // 2 + 1, dtype=np.float64) * SR / N_FFT
    points = mel_to_hz(np.linspace(hz_to_mel(fmin), hz_to_mel(fmax), n_mels + 2))
    fb = np.zeros((n_mels, bin_hz.size))
    for m in range(n_mels):
        lo, mid, hi = points[m], points[m + 1], points[m + 2]
        rising = (bin_hz - lo) / (mid - lo)
        falling = (hi - bin_hz) / (hi - mid)
        fb[m] = np.maximum(0.0, np.minimum(rising, falling)) * (2.0 / (hi - lo))
    return fb


def power_spectrum(x):
    n = x.size
    frames = -(-n // HOP)
    padded = np.concatenate([np.zeros(N_FFT // 2), x, np.zeros(N_FFT)])
    window = 0.5 - 0.5 * np.cos(2.0 * np.pi * np.arange(N_FFT) / N_FFT)
    out = np.empty((frames, N_FFT // 2 + 1))
    for t in range(frames):
        seg = padded[t * HOP:t * HOP + N_FFT]  # centred on sample t * HOP
        out[t] = np.abs(np.fft.rfft(seg * window)) ** 2
    return out


def dct2_ortho(n_out, n_in):
    k = np.arange(n_out)[:, None]
    n = np.arange(n_in)[None, :]
    d = np.cos(np.pi * k * (2 * n + 1) / (2.0 * n_in)) * np.sqrt(2.0 / n_in)
    d[0] /= np.sqrt(2.0)
    return d


def log_mel(power, n_mels):
    return 10.0 * np.log10(np.maximum(power @ mel_filterbank(n_mels).T, 1e-10))


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    x = np.load(sys.argv[1]).astype(np.float64).reshape(-1)
    out = sys.argv[2]
    power = power_spectrum(x)
    lm27 = log_mel(power, 27)
    np.save(os.path.join(out, "mfcc.npy"), lm27 @ dct2_ortho(27, 27).T)
    np.save(os.path.join(out, "logmel.npy"), log_mel(power, 40))
    np.save(os.path.join(out, "melfb27.npy"), mel_filterbank(27))
    np.save(os.path.join(out, "power.npy"), power)


if __name__ == "__main__":
    main()
