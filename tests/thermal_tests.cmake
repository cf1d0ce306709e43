# Surface temperature (docs/model.md §18, docs/verification.md 21).
rs_unit_test(test_thermal)
