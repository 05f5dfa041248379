#!/usr/bin/env python3
"""Would a plane term per range let the fractal codec reach its RMSE target? An estimate.

For 256 x 256 tiles of an SRTM .hgt file this computes, without building the codec:

1. the collage RMSE (the best fit of every range from the domain pool; the decoded attractor's
   error is close to it, a little above) of r x r ranges with 2r x 2r domains on a grid of step
   r, shrunk by 2x2 averaging, 8 isometries, |s| <= 15/16, unquantised, full search, for
     A: R ~ s D + o              (the codec today, seed 000)
     B: R ~ s D + o + a x + b y  (a plane term per range, orthogonalised like the mean);
2. the bytes per tile the two plane slopes of each range would cost: quantised to q metres per
   sample, MED-predicted from the left, upper and upper-left ranges, order-0 entropy.

Usage: scripts/fractal_plane_estimate.py FILE.hgt [--range 4] [--tiles 3]
Needs numpy. Figures quoted in docs/fractal.md.
"""
import argparse

import numpy as np


def load_hgt(path):
    data = np.fromfile(path, dtype=">i2")
    side = int(round(np.sqrt(data.size)))
    if side * side != data.size:
        raise SystemExit(f"{path}: not a square SRTM .hgt file ({data.size} samples)")
    return data.reshape(side, side).astype(np.float64)


def ranges_of(tile, r):
    n = tile.shape[0] // r
    return tile.reshape(n, r, n, r).transpose(0, 2, 1, 3)  # (rows, cols, r, r)


def domain_pool(tile, r):
    """Every 2r x 2r block at step r, shrunk to r x r, under the 8 isometries, flattened."""
    half = tile.shape[0] // 2
    shrunk = tile.reshape(half, 2, half, 2).mean(axis=(1, 3))
    step = max(1, r // 2)  # step r in the tile is r / 2 in the shrunk image
    blocks = []
    for y in range(0, half - r + 1, step):
        for x in range(0, half - r + 1, step):
            block = shrunk[y:y + r, x:x + r]
            for k in range(4):
                turned = np.rot90(block, k)
                blocks.append(turned.ravel())
                blocks.append(turned.T.ravel())
    return np.array(blocks)


def collage_rmse(ranges, domains, basis):
    """Best |R - fit| over the pool, with the fit's free terms spanning `basis`."""
    q, _ = np.linalg.qr(np.stack(basis, 1))
    complement = np.eye(q.shape[0]) - q @ q.T
    rp, dp = ranges @ complement, domains @ complement
    rn, dn = (rp ** 2).sum(1), (dp ** 2).sum(1) + 1e-12
    best = rn.copy()  # s = 0: the free terms alone
    for c in range(0, len(rp), 512):
        inner = rp[c:c + 512] @ dp.T
        s = np.clip(inner / dn, -15 / 16, 15 / 16)
        err = rn[c:c + 512, None] - 2 * s * inner + s * s * dn
        best[c:c + 512] = np.minimum(best[c:c + 512], err.min(1))
    return best.sum(), ranges.size


def med_entropy_bytes(values):
    left, up, upleft = (np.zeros_like(values) for _ in range(3))
    left[:, 1:], up[1:, :], upleft[1:, 1:] = values[:, :-1], values[:-1, :], values[:-1, :-1]
    low, high = np.minimum(left, up), np.maximum(left, up)
    pred = np.where(upleft >= high, low, np.where(upleft <= low, high, left + up - upleft))
    _, counts = np.unique((values - pred).ravel(), return_counts=True)
    p = counts / counts.sum()
    return -(counts * np.log2(p)).sum() / 8


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("hgt")
    parser.add_argument("--range", type=int, default=4, help="range side r (default 4)")
    parser.add_argument("--tiles", type=int, default=3, help="tiles per side sampled (default 3)")
    args = parser.parse_args()
    grid = load_hgt(args.hgt)
    r = args.range
    y, x = np.mgrid[0:r, 0:r]
    ones, xs, ys = np.ones(r * r), (x - x.mean()).ravel(), (y - y.mean()).ravel()
    spacing = (grid.shape[0] - 256) // max(1, args.tiles - 1)
    totals = {"A": [0.0, 0], "B": [0.0, 0]}
    slope_bytes = {0.5: 0.0, 1.0: 0.0, 2.0: 0.0}
    count = skipped = 0
    for ty in range(args.tiles):
        for tx in range(args.tiles):
            tile = grid[ty * spacing:ty * spacing + 256, tx * spacing:tx * spacing + 256]
            if (tile == -32768).any():  # SRTM voids (the codec sees them filled): skip the tile
                skipped += 1
                continue
            blocks = ranges_of(tile, r)
            ranges = blocks.reshape(-1, r * r)
            domains = domain_pool(tile, r)
            for name, basis in (("A", [ones]), ("B", [ones, xs, ys])):
                sq, n = collage_rmse(ranges, domains, basis)
                totals[name][0] += sq
                totals[name][1] += n
            offsets = np.arange(r) - (r - 1) / 2
            norm = r * (offsets ** 2).sum()
            a = (blocks * offsets[None, None, None, :]).sum((2, 3)) / norm
            b = (blocks * offsets[None, None, :, None]).sum((2, 3)) / norm
            for q in slope_bytes:
                slope_bytes[q] += sum(med_entropy_bytes(np.round(c / q).astype(int)) for c in (a, b))
            count += 1
    if count == 0:
        raise SystemExit(f"{args.hgt}: every sampled tile has voids")
    print(f"{args.hgt}: {count} tiles of 256 x 256 ({skipped} with voids skipped), {r}x{r} ranges")
    for name, label in (("A", "s D + o (today)"), ("B", "s D + o + plane")):
        sq, n = totals[name]
        print(f"  collage RMSE {label:18s} {np.sqrt(sq / n):6.2f} m")
    for q, total in slope_bytes.items():
        print(f"  plane slopes at {q} m/sample: {total / count:6.0f} bytes per tile")


if __name__ == "__main__":
    main()
