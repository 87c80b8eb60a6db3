"""A frame from Python against the CLI's frame time (issue 15: within 5%).

    PYTHONPATH=build/python /usr/bin/python3 python/bench_vs_cli.py SCENE.gltf \
        [--cli build/bin/quadra] [--rounds 5] [--frames 10] [--threads 2] [--size 1920x1080] [--reuse] [--depth]

Each round runs the CLI (`quadra render SCENE --frames K`: K timed frames
after one warm-up, its printed median) and then K timed Python renders after
one warm-up (their median), the order swapped every round so drift on a
shared machine hits both alike. Python's time is the whole `render` call: the
frame into numpy arrays (colour, and depth with --depth), their allocation
included unless --reuse (out=); the CLI's is its renderer's frame, which
without --out resolves no depth. Prints each round and the medians over the rounds.
"""
import argparse
import statistics
import subprocess
import time

import quadra


def cli_median(args, width, height):
    # Unlit, as the Python renders below (the CLI's default is pbr).
    out = subprocess.run([args.cli, "render", args.scene, "--shading", "unlit", "--width",
                          str(width), "--height", str(height), "--threads", str(args.threads),
                          "--frames", str(args.frames)],
                         check=True, capture_output=True, text=True).stdout
    line = next(l for l in out.splitlines() if l.startswith("quadra frame_ms"))
    return float(line.split("median=")[1].split()[0])


def python_median(renderer, scene, args, width, height):
    # warm-up, as the CLI's
    out = renderer.render(scene, width=width, height=height, depth=args.depth)
    times = []
    for _ in range(args.frames):
        start = time.perf_counter()
        renderer.render(scene, width=width, height=height, depth=args.depth,
                        out=out if args.reuse else None)
        times.append((time.perf_counter() - start) * 1000)
    return statistics.median(times)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("scene")
    parser.add_argument("--cli", default="build/bin/quadra")
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--frames", type=int, default=10)
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--size", default="1920x1080")
    parser.add_argument("--reuse", action="store_true",
                        help="render into the warm-up's arrays (out=) instead of new ones")
    parser.add_argument("--depth", action="store_true",
                        help="also return depth (the CLI's timed frame without --out has none)")
    args = parser.parse_args()
    width, height = (int(v) for v in args.size.split("x"))
    scene = quadra.load(args.scene)
    renderer = quadra.Renderer(threads=args.threads)
    cli, py = [], []
    for round_ in range(args.rounds):
        if round_ % 2 == 0:
            cli.append(cli_median(args, width, height))
            py.append(python_median(renderer, scene, args, width, height))
        else:
            py.append(python_median(renderer, scene, args, width, height))
            cli.append(cli_median(args, width, height))
        print(f"round {round_}: cli {cli[-1]:.2f} ms  python {py[-1]:.2f} ms")
    c, p = statistics.median(cli), statistics.median(py)
    print(f"median over {args.rounds} rounds: cli {c:.2f} ms  python {p:.2f} ms  "
          f"python/cli {p / c:.3f}")


if __name__ == "__main__":
    main()
