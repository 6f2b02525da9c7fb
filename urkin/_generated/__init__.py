"""Code generated from urkin.symbolic (plain numpy, committed; see ``python -m urkin.symbolic``)."""
