"""Helpers shared by the cross-checks: the crosscheck.json writer, the OpenSeesPy loader,
hex8 meshes for scikit-fem, and the lumped-mass leapfrog of scipy."""
