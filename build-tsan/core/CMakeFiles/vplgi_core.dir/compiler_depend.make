# Empty compiler generated dependencies file for vplgi_core.
# This may be replaced when dependencies are built.
