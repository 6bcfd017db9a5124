# Empty dependencies file for bench_contact_level.
# This may be replaced when dependencies are built.
