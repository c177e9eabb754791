"""Progress on the terminal for ``progress=True``: tqdm when it is installed, else lines on stderr."""

import sys


def terminal():
    """A callable (stage, fraction) that shows progress on stderr."""
    try:
        from tqdm import tqdm
    except ImportError:
        tqdm = None
    if tqdm is not None:
        bar = tqdm(total=100, unit="%", file=sys.stderr, leave=False)
        state = {"stage": None}

        def show(stage, fraction):
            if stage != state["stage"]:
                state["stage"] = stage
                bar.set_description(stage)
            bar.n = round(100 * fraction)
            bar.refresh()
            if stage in ("finish", "done"):
                bar.close()

        return show

    def show(stage, fraction):
        if sys.stderr.isatty():
            print(f"\rsurfgrow: {stage} {100 * fraction:3.0f}%", end="", file=sys.stderr)
            if stage in ("finish", "done"):
                print(file=sys.stderr)

    return show
