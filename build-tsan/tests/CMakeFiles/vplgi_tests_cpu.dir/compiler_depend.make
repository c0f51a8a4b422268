# Empty compiler generated dependencies file for vplgi_tests_cpu.
# This may be replaced when dependencies are built.
