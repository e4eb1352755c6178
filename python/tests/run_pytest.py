"""ctest's entry to the Python tests: runs pytest on this folder, or exits 77 (ctest: skipped) if pytest or NumPy
is missing (Debian: apt-get install python3-pytest python3-numpy)."""
import sys

# Under the guard: the Dask tests' worker processes are spawned, and import this script again without running it.
if __name__ == "__main__":
    try:
        import numpy  # noqa: F401  (the module returns NumPy arrays)
        import pytest
    except ImportError as e:
        print(f"python tests skipped: {e}", file=sys.stderr)
        sys.exit(77)

    sys.exit(pytest.main(["-q", "-p", "no:cacheprovider", *sys.argv[1:]]))
