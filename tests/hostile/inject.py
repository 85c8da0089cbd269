"""Run ``camcam`` with a fault injected at a chosen point (used by the hostile suite in subprocesses).

    python inject.py sigint-on-import MODULE -- ARGS...   Ctrl-C when MODULE starts to load
    python inject.py kill-at STEP K -- ARGS...            SIGKILL at the K-th call of files.STEP
    python inject.py no-exchange kill-at STEP K -- ARGS...  the same, without renameat2's exchange
    python inject.py kill-at STEP K publish -- TARGET       the same around a bare 2-file publish

``ARGS`` are camcam's arguments.  Faults are sent by the process to itself, so
where they land does not depend on timing.
"""

import os
import signal
import sys


def main() -> None:
    # Ctrl-C as a terminal delivers it: a process started in the background by a non-interactive shell
    # (`nohup pytest &`) inherits SIGINT ignored, and Python keeps it so; the faults below must not depend on
    # how the suite was launched
    signal.signal(signal.SIGINT, signal.default_int_handler)
    argv = sys.argv[1:]
    sep = argv.index("--")
    modes, args = argv[:sep], argv[sep + 1:]
    while modes:
        mode = modes.pop(0)
        if mode == "sigint-on-import":
            target = modes.pop(0)

            class Finder:
                fired = False

                def find_spec(self, name, path=None, target_=None):
                    if name == target and not Finder.fired:
                        Finder.fired = True
                        os.kill(os.getpid(), signal.SIGINT)
                    return None

            sys.meta_path.insert(0, Finder())
        elif mode == "no-exchange":
            import camcam.export.files as files

            files._swap = lambda a, b: False  # as on a kernel or file system without RENAME_EXCHANGE
        elif mode == "kill-at":
            step, k = modes.pop(0), int(modes.pop(0))
            import camcam.export.files as files

            original = getattr(files, step) if hasattr(files, step) else getattr(os, step)
            calls = [0]

            def wrapper(*a, **kw):
                calls[0] += 1
                if calls[0] == k:
                    os.kill(os.getpid(), signal.SIGKILL)
                return original(*a, **kw)

            if hasattr(files, step):
                setattr(files, step, wrapper)
            else:  # an os function as files uses it (os.rename)
                files.os = type(sys)("os_proxy")
                files.os.__dict__.update({k_: getattr(os, k_) for k_ in dir(os) if not k_.startswith("__")})
                setattr(files.os, step, wrapper)
        elif mode == "publish":  # no camcam command: publish a 2-file set over ARGS[0] with --force
            from camcam.export.files import OutputSet

            out = OutputSet(args[0], force=True)
            out.add("demo-motion.csv", "new")
            out.add("demo-svaj.png", "new")
            out.commit()
            return
        else:
            raise SystemExit(f"inject.py: unknown mode {mode}")
    sys.argv = ["camcam", *args]
    from camcam.cli import main_exit

    main_exit()


if __name__ == "__main__":
    main()
