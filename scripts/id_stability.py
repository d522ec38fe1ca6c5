#!/usr/bin/env python3
"""How well stable ids hold over a replay: per ground-truth object and for the
largest segments.

    lccp replay REC.oni --config robot -o PRED --save pcd
    lccp truth REC.oni -o TRUTH
    python3 scripts/id_stability.py PRED TRUTH [--field object] [--ignore-id 1]

Frames are paired by file name (replay and truth name them alike). For each
ground-truth region (mOSD labels: 1 table, 2 floor and wall, object n = label / 10)
the id it carries in a frame is the most common predicted id over its points; a
pair of consecutive frames keeps the id when both give the same. For the K largest
segments of each frame (by points, the ignored id left out), a pair keeps the id
when the most common id over the same pixels in the next frame is the segment's
own (organized frames: pixel i is the same ray in both); a merge of two
segments counts as a change there, whatever the ids do. So two more figures
for them: how often a largest segment of a frame carries an id handed out in
that very frame (a fresh id for something already in view), and for each of
the K largest segments of the first frame, the ids found over its pixels in
every frame (the most common one), as a sequence: a static wall should show
one id, or its id and the id of what it merges with. Standard library only.
"""
import argparse
import collections
import os
import struct
import sys


def lzf_decompress(data, size):
    """LZF (liblzf's format, as PCD's binary_compressed uses it)."""
    out = bytearray()
    i, n = 0, len(data)
    while i < n:
        ctrl = data[i]
        i += 1
        if ctrl < 32:
            out += data[i:i + ctrl + 1]
            i += ctrl + 1
            continue
        length = ctrl >> 5
        if length == 7:
            length += data[i]
            i += 1
        ref = len(out) - ((ctrl & 0x1F) << 8) - data[i] - 1
        i += 1
        length += 2
        if ref + length <= len(out):
            out += out[ref:ref + length]
        else:
            for k in range(length):
                out.append(out[ref + k])
    if len(out) != size:
        raise ValueError("LZF: %d bytes, expected %d" % (len(out), size))
    return bytes(out)


def read_pcd_fields(path, wanted):
    """The uint32 fields `wanted` of a PCD (binary or binary_compressed) as lists."""
    with open(path, "rb") as f:
        blob = f.read()
    header, pos = {}, 0
    while True:
        end = blob.index(b"\n", pos)
        words = blob[pos:end].decode().split()
        pos = end + 1
        if words and not words[0].startswith("#"):
            header[words[0]] = words[1:]
            if words[0] == "DATA":
                break
    fields, sizes = header["FIELDS"], [int(s) for s in header["SIZE"]]
    counts = [int(c) for c in header.get("COUNT", ["1"] * len(fields))]
    points = int(header["POINTS"][0])
    kind = header["DATA"][0]
    out = {}
    if kind == "binary_compressed":
        packed, raw = struct.unpack_from("<II", blob, pos)
        data = lzf_decompress(blob[pos + 8:pos + 8 + packed], raw)
        offset = 0
        for name, size, count in zip(fields, sizes, counts):
            if name in wanted:
                out[name] = list(memoryview(data[offset:offset + size * count * points]).cast("I"))
            offset += size * count * points
    elif kind == "binary":
        stride = sum(s * c for s, c in zip(sizes, counts))
        offset = 0
        for name, size, count in zip(fields, sizes, counts):
            if name in wanted:
                column = bytearray()
                for p in range(points):
                    start = pos + p * stride + offset
                    column += blob[start:start + 4]
                out[name] = list(memoryview(bytes(column)).cast("I"))
            offset += size * count
    else:
        raise ValueError(path + ": DATA " + kind + " not supported")
    return out


def majority(ids):
    counts = collections.Counter(i for i in ids if i != 0)
    return counts.most_common(1)[0][0] if counts else 0


def truth_regions(labels):
    """Point indices per ground-truth region: 'table', 'floor+wall', 'object n'."""
    regions = collections.defaultdict(list)
    for i, label in enumerate(labels):
        if label == 1:
            regions["table"].append(i)
        elif label == 2:
            regions["floor+wall"].append(i)
        elif label >= 10:
            regions["object %d" % (label // 10)].append(i)
    return regions


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("pred")
    parser.add_argument("truth")
    parser.add_argument("--field", default="object", help="predicted id field (object; label for one level)")
    parser.add_argument("--ignore-id", type=int, default=1, help="id left out of the largest segments (the support)")
    parser.add_argument("--largest", type=int, default=5)
    parser.add_argument("--min-points", type=int, default=200, help="a region smaller in a frame is not in view")
    args = parser.parse_args()
    names = sorted(n for n in os.listdir(args.pred) if n.startswith("frame_") and n.endswith(".pcd"))
    held = collections.defaultdict(lambda: [0, 0])  # region -> [pairs kept, pairs]
    ids_seen = collections.defaultdict(list)
    rank_held = [[0, 0] for _ in range(args.largest)]
    rank_fresh = [[0, 0] for _ in range(args.largest)]
    first_masks, mask_ids, seen_ids = None, [], set()
    previous = None
    for name in names:
        pred = read_pcd_fields(os.path.join(args.pred, name), {args.field, "label"})
        ids = pred.get(args.field) or pred["label"]
        truth = read_pcd_fields(os.path.join(args.truth, name), {"label"})["label"]
        regions = {r: majority(ids[i] for i in pixels)
                   for r, pixels in truth_regions(truth).items() if len(pixels) >= args.min_points}
        for region, rid in regions.items():
            if not ids_seen[region] or ids_seen[region][-1] != rid:
                ids_seen[region].append(rid)
        if previous is not None:
            prev_regions, prev_ids = previous
            for region, rid in regions.items():
                if region in prev_regions:
                    held[region][0] += rid == prev_regions[region]
                    held[region][1] += 1
            sizes = collections.Counter(i for i in prev_ids if i not in (0, args.ignore_id))
            for rank, (sid, _) in enumerate(sizes.most_common(args.largest)):
                pixels = [i for i, v in enumerate(prev_ids) if v == sid]
                rank_held[rank][0] += majority(ids[i] for i in pixels) == sid
                rank_held[rank][1] += 1
        ranked = collections.Counter(i for i in ids if i not in (0, args.ignore_id)).most_common(args.largest)
        if first_masks is None:
            first_masks = [[i for i, v in enumerate(ids) if v == sid] for sid, _ in ranked]
            mask_ids = [[] for _ in first_masks]
        else:
            for rank, (sid, _) in enumerate(ranked):
                rank_fresh[rank][0] += sid not in seen_ids
                rank_fresh[rank][1] += 1
        for mask, seq in zip(first_masks, mask_ids):
            mid = majority(ids[i] for i in mask)
            if not seq or seq[-1] != mid:
                seq.append(mid)
        seen_ids.update(ids)
        previous = (regions, ids)
    print("frames %d (%s)" % (len(names), args.pred))
    for region in sorted(held):
        kept, pairs = held[region]
        print("%-12s id kept in %3d of %3d frame pairs (%5.1f %%); ids: %s" %
              (region, kept, pairs, 100.0 * kept / max(pairs, 1), " ".join(map(str, ids_seen[region][:12]))))
    for rank, ((kept, pairs), (fresh, frames)) in enumerate(zip(rank_held, rank_fresh)):
        print("largest #%d   id kept in %3d of %3d frame pairs (%5.1f %%); a fresh id in %3d of %3d frames" %
              (rank + 1, kept, pairs, 100.0 * kept / max(pairs, 1), fresh, frames))
    for rank, seq in enumerate(mask_ids):
        print("frame 0's #%d: %d distinct ids over its pixels, %d changes: %s" %
              (rank + 1, len(set(seq)), len(seq) - 1, " ".join(map(str, seq[:16])) + (" ..." if len(seq) > 16 else "")))


if __name__ == "__main__":
    sys.exit(main())
