namespace kimp { int pipeline_placeholder_tmp() { return 0; } }
