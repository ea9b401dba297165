/* Runs a fuzz target over files (or every file of folders), without libFuzzer: make check replays each
 * target's seed corpus and the inputs of fixed bugs with the ordinary (sanitizer) build. */
#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static int replay_file(const char *path)
{
	FILE *f = fopen(path, "rb");
	if (!f) {
		fprintf(stderr, "replay: cannot read %s\n", path);
		return -1;
	}
	size_t cap = 1 << 16, size = 0, n;
	uint8_t *data = malloc(cap);
	while (data && (n = fread(data + size, 1, cap - size, f)) > 0) {
		size += n;
		if (size == cap) {
			uint8_t *grown = realloc(data, cap *= 2);
			if (!grown)
				break;
			data = grown;
		}
	}
	fclose(f);
	if (!data)
		return -1;
	LLVMFuzzerTestOneInput(data, size);
	free(data);
	return 0;
}

int main(int argc, char **argv)
{
	int count = 0, failed = 0;
	for (int i = 1; i < argc; i++) {
		struct stat st;
		if (stat(argv[i], &st) == 0 && S_ISDIR(st.st_mode)) {
			DIR *d = opendir(argv[i]);
			struct dirent *de;
			while (d && (de = readdir(d))) {
				if (de->d_name[0] == '.')
					continue;
				char path[4096];
				snprintf(path, sizeof path, "%s/%s", argv[i], de->d_name);
				failed += replay_file(path) != 0;
				count++;
			}
			if (d)
				closedir(d);
		} else {
			failed += replay_file(argv[i]) != 0;
			count++;
		}
	}
	printf("replayed %d inputs\n", count - failed);
	return failed || count == 0 ? 1 : 0;
}
