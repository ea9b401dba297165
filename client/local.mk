# client: aalab, the command line: one file per subcommand (cmd_*.c), run in-process or through aalabd,
# and what they share (argument parsing, the protocol connection, tables, output folders).
aalab_SOURCES = client/aalab.c client/client.h client/job_args.c client/method_files.c \
	client/out_dir.h client/out_dir.c client/remote.c client/table.c client/suite_table.c \
	client/verdict_table.c client/verdict_lines.c client/progress.c \
	client/cmd_run.c client/cmd_list.c client/cmd_suites.c client/cmd_diff.c client/cmd_compare.c \
	client/cmd_merge.c client/cmd_slurm.c client/cmd_submit.c client/cmd_watch.c client/cmd_status.c \
	client/cmd_jobs.c client/cmd_cancel.c client/cmd_get.c client/cmd_cache.c
aalab_LDADD = $(ENGINE_LIBS)
