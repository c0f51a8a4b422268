# CMAKE generated file: DO NOT EDIT!
# Timestamp file for compiler generated dependencies management for vplgi_tests_cpu.
