# Empty compiler generated dependencies file for tylmp.
# This may be replaced when dependencies are built.
