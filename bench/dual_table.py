#!/usr/bin/env python3
"""Markdown tables for bench/README.md from dual_bench's JSON output.

    bench/dual_table.py bench-data/dual_bench.json
"""
import json
import sys
from collections import defaultdict


def main(path):
    runs = json.load(open(path))["benchmarks"]
    by = defaultdict(dict)  # (domain, size) -> kind -> run
    random = []
    for r in runs:
        parts = r["name"].split("/")
        if parts[0] == "ClassifyDualRandom":
            random.append(r)
        else:
            by[(parts[1], int(parts[2]))][parts[0]] = r
    print("| domain | target | tets | read+classify µs/tet | classify+dual µs/tet (mean) | best | best: user | best: sys | peak B/tet | dual cells "
          "| validate | order | topology | classify | points | sides | faces | cleanup "
          "| star exact ns/tet | star double ns/tet | exact/double | exact share |")
    print("|" + "---|" * 22)
    order = {"cube": 0, "twomat": 1, "fichera": 2, "fracture": 3}
    for (dom, n) in sorted(by, key=lambda k: (k[1], order.get(k[0], 9))):
        k = by[(dom, n)]
        cd, rc, se, sd = k.get("ClassifyDual"), k.get("ReadClassify"), k.get("StarExact"), k.get("StarDouble")
        stages = [cd[s] for s in ("s1_validate", "s2_order", "s3_topology", "s4_classify", "s5_points",
                                  "s6_sides", "s7_faces", "s8_cleanup")]
        ratio = se["ns_per_tet"] / sd["ns_per_tet"]
        print(f"| {dom} | {n} | {int(cd['tets'])} | {rc['us_per_tet']:.2f} | {cd['us_per_tet']:.2f} | {cd['us_per_tet_best']:.2f} | "
              f"{cd.get('user_us_per_tet_best', float('nan')):.2f} | {cd.get('sys_us_per_tet_best', float('nan')):.2f} | "
              f"{cd['peak_B_per_tet']:.0f} | {int(cd['cells'])} | " + " | ".join(f"{x:.3f}" for x in stages) +
              f" | {se['ns_per_tet']:.1f} | {sd['ns_per_tet']:.1f} | {ratio:.2f} | {se['exact_share']:.2g} |")
    if random:
        print()
        print("| random Delaunay, target | tets | classify+dual µs/tet (mean) | best | best: user | best: sys | peak B/tet | validate | order | topology "
              "| classify | points | sides | faces | cleanup |")
        print("|" + "---|" * 15)
        for r in random:
            stages = [r[s] for s in ("s1_validate", "s2_order", "s3_topology", "s4_classify", "s5_points",
                                     "s6_sides", "s7_faces", "s8_cleanup")]
            print(f"| {r['name'].split('/')[1]} | {int(r['tets'])} | {r['us_per_tet']:.2f} | {r['us_per_tet_best']:.2f} | "
                  f"{r.get('user_us_per_tet_best', float('nan')):.2f} | {r.get('sys_us_per_tet_best', float('nan')):.2f} | "
                  f"{r['peak_B_per_tet']:.0f} | " + " | ".join(f"{x:.3f}" for x in stages) + " |")


if __name__ == "__main__":
    main(sys.argv[1])
