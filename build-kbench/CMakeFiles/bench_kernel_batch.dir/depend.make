# Empty dependencies file for bench_kernel_batch.
# This may be replaced when dependencies are built.
