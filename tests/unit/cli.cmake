add_test(NAME test_cli COMMAND ${PROJECT_SOURCE_DIR}/tests/cli/test_cli.sh $<TARGET_FILE:lvsim_cli>)
add_test(NAME test_symbols COMMAND ${PROJECT_SOURCE_DIR}/tests/cli/check_symbols.sh
         $<TARGET_FILE:lvsim> $<TARGET_FILE:lvsim_post>)
