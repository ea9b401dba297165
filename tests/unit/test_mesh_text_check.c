/* aalab's own reading of OBJ (+ .mtl), OFF, PLY and STL files before assimp (mesh_text_check.c): good
 * files of each format pass, and each bad one is refused saying what is wrong where. Then through the scene
 * loader: the OFF file fuzz_mesh found crashing assimp 5.2, a bad .mtl, a format aalab does not read. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <cmocka.h>

#include "scene/mesh_text_check.h"
#include "scene/scene.h"

#define OBJ AA_MESH_FORMAT_OBJ
#define MTL AA_MESH_FORMAT_MTL
#define OFF AA_MESH_FORMAT_OFF
#define PLY AA_MESH_FORMAT_PLY
#define STL AA_MESH_FORMAT_STL

#define OFF_TRI "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n"
#define PLY_HEAD "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n" \
	"element face 1\nproperty list uchar int vertex_indices\nend_header\n"
#define STL_FACET "facet normal 0 0 1\n outer loop\n  vertex 0 0 0\n  vertex 1 0 0\n  vertex 0 1 0\n endloop\nendfacet\n"

static const struct {
	enum aa_mesh_format format;
	const char *text;
	const char *says; /* NULL: the file is good */
} cases[] = {
	/* OFF */
	{OFF, OFF_TRI "3 0 1 2\n", NULL},
	{OFF, "# made by hand\nOFF\n# counts\n3 1 0\n\n0 0 0\n1 0 0\n0 1 0\n\n3 0 1 2 0.5 0.5 0.5 1\n# end\n", NULL},
	{OFF, "COFF\n3 1 0\n0 0 0 1 0 0 1\n1 0 0 0 1 0 1\n0 1 0 0 0 1 1\n3 0 1 2\n", NULL},
	{OFF, "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n", NULL},
	/* the input fuzz_mesh found: a face of 11 vertices (assimp drops it and crashes later), past the vertices */
	{OFF, "OFF\n1 1 0\n0 0 0\n11 0\n0 0 0\n1 0 00\n 01 3 0 1 2\n", "line 2: the counts say 1 vertices and 1 faces"},
	{OFF, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n11 0 1 2 0 1 2 0 1 2 0 1\n", "line 6: face 0 has 11 vertices: OFF faces must have 3 to 9"},
	{OFF, OFF_TRI "3 0 1 3\n", "line 6: face 0 names vertex 3, but the file has 3 vertices"},
	{OFF, OFF_TRI "3 0 1 -2\n", "line 6: face 0: '-2' is not a whole number"},
	{OFF, OFF_TRI "2 0 1\n", "line 6: face 0 has 2 vertices"},
	{OFF, OFF_TRI "3 0 1\n", "line 6: face 0 says 3 vertices, the line has 2 indices"},
	{OFF, OFF_TRI "3 0 1 2\n3 0 1 2\n", "line 7: more data after the 1 faces"},
	{OFF, "OFF\n3 2 0\n0.0000 0.0000 0.0000\n1.0000 0 0\n0 1.0000 0\n3 0 1 2\n", "the counts say 2 faces, the file ends after 1"},
	{OFF, "OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n", "line 2: the counts say 4 vertices and 1 faces, more than the file's"},
	{OFF, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1\n3 0 1 2\n", "line 5: vertex 2 must have 3 values (x y z), it has 2"},
	{OFF, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 nan 0\n3 0 1 2\n", "line 5: vertex 2: 'nan' is not a finite number"},
	{OFF, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 2e7 0\n3 0 1 2\n", "line 5: vertex 2 is at (0, 2e+07, 0): positions must be within 1e+07"},
	{OFF, "OFF\n3 1 0\n0 0 0\n# a comment\n1 0 0\n0 1 0\n3 0 1 2\n", "line 4: a comment or blank line among the vertices"},
	{OFF, "3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "line 1: the file must start with OFF"},
	{OFF, "4OFF\n3 1 0\n0 0 0 1\n1 0 0 1\n0 1 0 1\n3 0 1 2\n", "line 1: the file must start with OFF"},
	{OFF, "OFF\n3 1\n0 0 0\n", "line 2: the counts line must hold 3 whole numbers"},
	{OFF, "OFF\n3 1 0\n0 0 0\n1 0 0\x01\n0 1 0\n3 0 1 2\n", "line 4: holds a byte that is not text (0x01"},
	{OFF, "OFF\n3 1 0\n0 0 0\r1 0 0\n0 1 0\n3 0 1 2\n", "line 3: holds a byte that is not text (0x0d"},
	/* OBJ */
	{OBJ, "# a triangle\no tri\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\ns off\ng side\n"
	      "usemtl paint\nf 1/1/1 2/2/1 3/3/1\nf -3//-1 -2//-1 -1//-1\nl 1 2\np 3\n", NULL},
	{OBJ, "v 0 0 0\r\nv 1 0 0 1\r\nv 0 1 0 0.5 0.5 0.5\r\nf 1 2 3\r\n", NULL},
	{OBJ, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", "line 4: a face names a vertex that does not exist: vertex (v) 9, but the file has 3"},
	{OBJ, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\n", "line 5: a face names a vertex that does not exist: vertex (v) 4, but the file has 3"},
	{OBJ, "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1e39\nf 1 2 3\n", "line 4: normal (vn) 0: '1e39' is not a finite number"},
	{OBJ, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/4 2/1 3/1\nvt 0 0\n", "line 4: a face names a vertex that does not exist: texture coordinate (vt) 4, but the file has 1"},
	{OBJ, "v 0 0 0\nv 1 0 0\nf -3 1 2\nv 0 1 0\n", "line 3: '-3' names vertex (v) -3, before the first"},
	{OBJ, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "line 4: '0' is not a vertex reference"},
	{OBJ, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", "line 4: a face (f) needs at least 3 vertices, it has 2"},
	{OBJ, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1/1/1 2 3\n", "line 4: '1/1/1/1' is not a vertex reference"},
	{OBJ, "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2 3\n", "line 5: '2' is not in the form of the face's first vertex"},
	{OBJ, "v 0 0 0\nv 1 0 0\nv 0 1e30 0\nf 1 2 3\n", "line 3: vertex 2 is at (0, 1e+30, 0): positions must be within 1e+07"},
	{OBJ, "v 0 0 0\nv 1 0 0\nv 0 1 0 0\nf 1 2 3\n", "line 3: vertex 2 (v) has w = 0"},
	{OBJ, "v 0 0 0\nv 1 0 inf\nv 0 1 0\nf 1 2 3\n", "line 2: vertex 1 (v): 'inf' is not a finite number"},
	{OBJ, "v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n", "line 2: vertex 1 (v) must be x y z, x y z w or x y z r g b, it has 2"},
	{OBJ, "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 1\nf 1 2 3\n", "line 4: normal (vn) 0 must have 3 values, it has 2"},
	{OBJ, "v 0 0 0\nv 1 0 0\nv 0 1 0\n", "has no faces (f)"},
	{OBJ, "v 0 0 0\nv 1 0 0\nv 0 1 0\ncurv 0 1 1 2\nf 1 2 3\n", "line 4: 'curv' is not an OBJ statement aalab reads"},
	{OBJ, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 \\\n3\n", "line 4: a line continued with \\ is not supported"},
	{OBJ, "v 0 0 0\nv 1 0 0\nv 0 1 0\ns smooth\nf 1 2 3\n", "line 4: a smoothing group (s) is off or a whole number"},
	{OBJ, "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl\nf 1 2 3\n", "line 4: usemtl names one material"},
	{OBJ, "v 0 0 0\nv 1 0 0\nv 0 1 0\np 1/1\nf 1 2 3\n", "line 4: a point (p) names vertices alone"},
	{OBJ, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\0\n", "line 4: holds a byte that is not text (0x00"},
	/* .mtl */
	{MTL, "# paint\nnewmtl paint\nKa 0 0 0\nKd 0.8 0.2 0.2\nKs 0.5\nNs 64\nd -halo 0.5\nillum 2\nmap_Kd -s 2 2 1 a b.png\n", NULL},
	{MTL, "Kd 1 1 1\n", "line 1: 'Kd' before the first newmtl"},
	{MTL, "newmtl a\nKd 1 1\n", "line 2: Kd must have 1 or 3 numbers, it has 2 values"},
	{MTL, "newmtl a\nKd 1 nan 1\n", "line 2: Kd: 'nan' is not a finite number"},
	{MTL, "newmtl a\nNs\n", "line 2: Ns must have 1 number, it has 0 values"},
	{MTL, "newmtl a\nmap_Kd\n", "line 2: map_Kd names no texture file"},
	{MTL, "newmtl a\nKx 1\n", "line 2: 'Kx' is not a material statement aalab reads"},
	{MTL, "newmtl\n", "line 1: newmtl names one material"},
	/* PLY (ASCII) */
	{PLY, PLY_HEAD "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", NULL},
	{PLY, "ply\r\nformat ascii 1.0\r\ncomment by hand\r\nelement vertex 3\r\nproperty double x\r\nproperty double y\r\n"
	      "property double z\r\nproperty uchar red\r\nelement face 1\r\nproperty list uint uint vertex_index\r\n"
	      "property float quality\r\nend_header\r\n0 0 0 255\r\n1 0 0 0\r\n0 1 0 7\r\n3 0 1 2 0.5\r\n", NULL},
	{PLY, PLY_HEAD "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "line 13: face 0 names vertex 3, but the file has 3 vertices"},
	{PLY, PLY_HEAD "0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", "line 13: face 0 names vertex -1"},
	{PLY, PLY_HEAD "0 0 0\n1 0 0\n0 1 0\n2 0 1\n", "line 13: face 0 has 2 vertices"},
	{PLY, PLY_HEAD "0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n", "line 13: face 0 has 4 vertices (at least 3, and the line has 3 values"},
	{PLY, PLY_HEAD "0 0 0\n1 0 0\n0 1 0\n3 0 1 2 0\n", "line 13: face 0 has 5 values, its properties take 4"},
	{PLY, PLY_HEAD "0 0 0\n1 0 0\n0 3e9 0\n3 0 1 2\n", "line 12: vertex 2 is at (0, 3e+09, 0): positions must be within 1e+07"},
	{PLY, PLY_HEAD "0 0 0\n1 0 0\n0 1 nan\n3 0 1 2\n", "line 12: vertex 2: 'nan' is not a finite number"},
	{PLY, PLY_HEAD "0 0 0\n1 0 0\n0 1 0\n256 0 1 2\n", "line 13: face 0: '256' is not a whole number from 0 to 255"},
	{PLY, PLY_HEAD "0 0 0\n1 0 0\n", "the header declares 3 vertex elements, the file ends after 2"},
	{PLY, PLY_HEAD "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n", "line 14: more data after the 1 faces"},
	{PLY, "ply\nformat ascii 1.0\nelement vertex 3\nproperty float xy\nproperty float z\nelement face 1\n"
	      "property list uchar int vertex_indices\xff\n", "line 7: holds a byte that is not text (0xff"},
	{PLY, "ply\nformat ascii 1.0\nelement vertex 3\npropertvertex index\nend_header\n",
	 "line 4: 'propertvertex' is not one of ply, format, comment, obj_info, element, property, end_header"},
	{PLY, "ply\nformat ascii 1.0\nelement vertex 3\nproperty float y\nproperty float z\nelement face 1\n"
	      "property list uchar int vertex_indices\nend_header\n", "element vertex has no property x"},
	{PLY, "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float x\n", "line 5: property 'x' is declared twice"},
	{PLY, "ply\nformat ascii 1.0\nelement vertex 3\nproperty list uchar float x\n", "line 4: list property 'x': aalab reads one list"},
	{PLY, "ply\nformat ascii 1.0\nelement vertex 3\nproperty half x\n", "line 4: property 'x': 'half' is not a PLY type"},
	{PLY, "ply\nformat ascii 2.0\n", "line 2: one format line"},
	{PLY, "ply\nformat ascii 1.0\nelement edge 3\n", "line 3: element 'edge': aalab reads the elements vertex and then face"},
	{PLY, "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
	      "element face 1\nproperty list float int vertex_indices\n", "line 8: list property 'vertex_indices' must have integer count"},
	{PLY, "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
	      "element face 1\nproperty list uchar int vertex_indices\n", "the header has no end_header line"},
	{PLY, "ply\nelement vertex 3\n", "line 2: the second line must be the format line"},
	{PLY, "ply\ncomment first\nformat ascii 1.0\n", "line 2: the second line must be the format line"},
	{PLY, "pl\n", "line 1: a PLY file starts with the line ply"},
	/* STL (ASCII) */
	{STL, "solid t\n" STL_FACET STL_FACET "endsolid t\nsolid u\n" STL_FACET "endsolid u\n", NULL},
	{STL, "solid t\n" STL_FACET, "ends before endsolid"},
	{STL, "solid t\nendsolid t\n", "has no facets"},
	{STL, "solid t\nfacet normal 0 0\n", "line 2: expected 'facet normal nx ny nz' or 'endsolid'"},
	{STL, "solid t\nfacet normal 0 0 nan\n", "line 2: triangle 0 normal: 'nan' is not a finite number"},
	{STL, "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\n", "line 6: expected 'vertex x y z'"},
	{STL, "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nvertex 0 1 0\n",
	 "line 7: expected 'endloop'"},
	{STL, "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 -1e8 0\n",
	 "line 6: vertex 2 is at (0, -1e+08, 0): positions must be within 1e+07"},
	{STL, "solid t\n" STL_FACET "endsolid t\nfacet\n", "line 10: expected 'solid' or the end of the file after endsolid"},
	{STL, "sold t\n", "is neither ASCII STL (starting with solid) nor binary STL (at least 84 bytes)"},
	{STL, "\nsolid t\n" STL_FACET "endsolid t\n", "is neither ASCII STL (starting with solid)"},
	{STL, " \tsolid t\n" STL_FACET "endsolid t\n", NULL},
};

static void test_cases(void **state)
{
	(void)state;
	int failures = 0;
	for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
		char why[600] = "";
		/* the table's strings hold NUL bytes in one case: up to the last character before the terminator */
		size_t size = strlen(cases[i].text);
		if (cases[i].says && strstr(cases[i].says, "0x00"))
			size += 2;
		int rc = aa_mesh_text_check(cases[i].format, cases[i].text, size, NULL, NULL, why, sizeof why);
		if (cases[i].says ? rc != -1 || !strstr(why, cases[i].says) : rc != 0) {
			print_error("case %zu (%.40s...): got %d '%s', wanted %s\n", i, cases[i].text, rc, why,
				    cases[i].says ? cases[i].says : "good");
			failures++;
		}
	}
	assert_int_equal(failures, 0);
}

/* ---- binary files */

static size_t put_f32(unsigned char *p, float f, bool big)
{
	unsigned char b[4];
	memcpy(b, &f, 4); /* the machine is little-endian (x86-64) */
	for (int k = 0; k < 4; k++)
		p[k] = b[big ? 3 - k : k];
	return 4;
}

static size_t put_i32(unsigned char *p, int32_t v, bool big)
{
	uint32_t u = (uint32_t)v;
	for (int k = 0; k < 4; k++)
		p[big ? 3 - k : k] = (unsigned char)(u >> (8 * k));
	return 4;
}

/* A binary PLY triangle: `last` is its third index, `n` its vertex count, `extra` bytes more at the end. */
static size_t binary_ply(unsigned char *out, bool big, int n, int32_t last, float y2, int extra)
{
	size_t at = (size_t)sprintf((char *)out, "ply\nformat binary_%s_endian 1.0\nelement vertex 3\nproperty float x\n"
				    "property float y\nproperty float z\nelement face 1\nproperty list uchar int "
				    "vertex_indices\nend_header\n", big ? "big" : "little");
	float v[9] = {0, 0, 0, 1, 0, 0, 0, y2, 0};
	for (int k = 0; k < 9; k++)
		at += put_f32(out + at, v[k], big);
	out[at++] = (unsigned char)n;
	int32_t idx[3] = {0, 1, last};
	for (int k = 0; k < 3; k++)
		at += put_i32(out + at, idx[k], big);
	memset(out + at, 0, (size_t)extra);
	return at + (size_t)extra;
}

static int check(enum aa_mesh_format f, const unsigned char *data, size_t size, char *why)
{
	why[0] = '\0';
	return aa_mesh_text_check(f, (const char *)data, size, NULL, NULL, why, 600);
}

static void test_binary_ply(void **state)
{
	(void)state;
	unsigned char buf[1024];
	char why[600];
	for (int big = 0; big < 2; big++) {
		assert_int_equal(check(PLY, buf, binary_ply(buf, big, 3, 2, 1, 0), why), 0);
		assert_int_equal(check(PLY, buf, binary_ply(buf, big, 3, 3, 1, 0), why), -1);
		assert_non_null(strstr(why, "face 0 (byte 45 of the data) names vertex 3, but the file has 3 vertices"));
		assert_int_equal(check(PLY, buf, binary_ply(buf, big, 3, -1, 1, 0), why), -1);
		assert_non_null(strstr(why, "names vertex -1"));
		assert_int_equal(check(PLY, buf, binary_ply(buf, big, 2, 2, 1, 0), why), -1);
		assert_non_null(strstr(why, "face 0 (byte 36 of the data) has 2 vertices, at least 3"));
		assert_int_equal(check(PLY, buf, binary_ply(buf, big, 3, 2, 5e7f, 0), why), -1);
		assert_non_null(strstr(why, "vertex 2 is at (0, 5e+07, 0): positions must be within 1e+07"));
		assert_int_equal(check(PLY, buf, binary_ply(buf, big, 3, 2, 1.0f / 0.0f, 0), why), -1);
		assert_non_null(strstr(why, "vertex 2 (byte 28 of the data): property y is not a finite number"));
		assert_int_equal(check(PLY, buf, binary_ply(buf, big, 3, 2, 1, 3), why), -1);
		assert_non_null(strstr(why, "3 bytes after the last face the header declares"));
		assert_int_equal(check(PLY, buf, binary_ply(buf, big, 3, 2, 1, 0) - 1, why), -1);
		assert_non_null(strstr(why, "declares 1 face elements of at least 13 bytes, more than the 12 bytes of data left"));
		assert_int_equal(check(PLY, buf, binary_ply(buf, big, 200, 2, 1, 0), why), -1);
		assert_non_null(strstr(why, "the file ends in its 200 indices"));
	}
	/* a count that asks for more than the file holds is refused before anything is read */
	size_t n = binary_ply(buf, false, 3, 2, 1, 0);
	char *vertex = strstr((char *)buf, "vertex 3\n");
	memcpy(vertex, "vertex 9", 8);
	assert_int_equal(check(PLY, buf, n, why), -1);
	assert_non_null(strstr(why, "the header declares 9 vertex elements of at least 12 bytes, more than the 49 bytes"));
	/* CRLF header lines would put the binary data one byte off */
	unsigned char crlf[1024];
	size_t m = (size_t)sprintf((char *)crlf, "ply\r\nformat binary_little_endian 1.0\r\n");
	memcpy(crlf + m, buf + 36, n - 36);
	assert_int_equal(check(PLY, crlf, m + n - 36, why), -1);
	assert_non_null(strstr(why, "a binary PLY header's lines must end with a line feed alone"));
}

/* A binary STL of `count` triangles as the header says, `have` in the file. */
static size_t binary_stl(unsigned char *out, uint32_t count, uint32_t have, float z)
{
	memset(out, 0, 84);
	memcpy(out, "solid but binary", 16); /* exporters write that; the size decides */
	put_i32(out + 80, (int32_t)count, false);
	size_t at = 84;
	for (uint32_t t = 0; t < have; t++) {
		float v[12] = {0, 0, 1, 0, 0, z, 1, 0, 0, 0, 1, 0};
		for (int k = 0; k < 12; k++)
			at += put_f32(out + at, v[k], false);
		out[at++] = 0, out[at++] = 0;
	}
	return at;
}

static void test_binary_stl(void **state)
{
	(void)state;
	unsigned char buf[1024];
	char why[600];
	assert_int_equal(check(STL, buf, binary_stl(buf, 2, 2, 0), why), 0);
	assert_int_equal(check(STL, buf, binary_stl(buf, 2, 2, 0.0f / 0.0f), why), -1);
	assert_non_null(strstr(why, "triangle 0 (byte 84) has a position that is not a finite number"));
	assert_int_equal(check(STL, buf, binary_stl(buf, 2, 2, 3e7f), why), -1);
	assert_non_null(strstr(why, "triangle 0 (byte 84): vertex 0 is at (0, 0, 3e+07)"));
	assert_int_equal(check(STL, buf, binary_stl(buf, 0, 0, 0), why), -1);
	assert_non_null(strstr(why, "a binary STL file of no triangles"));
	/* the header's count does not match the size: and the file is not text either */
	size_t n = binary_stl(buf, 3, 2, 0);
	assert_int_equal(check(STL, buf, n, why), -1);
	assert_non_null(strstr(why, "line 1: holds a byte that is not text"));
	buf[0] = 'x';
	assert_int_equal(check(STL, buf, n, why), -1);
	assert_non_null(strstr(why, "is neither ASCII STL (starting with solid) nor binary STL: its header says 3 "
				    "triangles, 234 bytes, the file has 184"));
	/* a count whose 32-bit size wraps round to the file's size: assimp would take it for binary */
	assert_int_equal(check(STL, buf, binary_stl(buf, 2147483650u, 2, 0), why), -1);
	assert_non_null(strstr(why, "binary STL header says 2147483650 triangles"));
}

/* Lines longer than assimp's OFF reader copies safely, or than any text line aalab reads. */
static void test_long_lines(void **state)
{
	(void)state;
	char *text = malloc(70100), why[600];
	assert_non_null(text);
	int n = sprintf(text, "OFF\n3 1 0\n0 0 0");
	memset(text + n, ' ', 3995); /* the line is 4000 characters: still read */
	n += 3995;
	n += sprintf(text + n, "\n1 0 0\n0 1 0\n3 0 1 2\n");
	assert_int_equal(aa_mesh_text_check(OFF, text, (size_t)n, NULL, NULL, why, sizeof why), 0);
	memmove(text + 17, text + 16, (size_t)n - 16); /* 4001 */
	assert_int_equal(aa_mesh_text_check(OFF, text, (size_t)n + 1, NULL, NULL, why, sizeof why), -1);
	assert_non_null(strstr(why, "line 3: longer than 4000 characters"));
	n = sprintf(text, "v 0 0 0\nv 1 0 0\nv 0 1 0\n#");
	memset(text + n, 'x', 65535); /* the comment line is 65536 characters */
	n += 65535;
	n += sprintf(text + n, "\nf 1 2 3\n");
	assert_int_equal(aa_mesh_text_check(OBJ, text, (size_t)n, NULL, NULL, why, sizeof why), 0);
	memmove(text + 25, text + 24, (size_t)n - 24);
	assert_int_equal(aa_mesh_text_check(OBJ, text, (size_t)n + 1, NULL, NULL, why, sizeof why), -1);
	assert_non_null(strstr(why, "line 4: longer than 65536 characters"));
	free(text);
}

/* ---- through the scene loader */

static char dir[256];

static void write_file(const char *name, const char *text)
{
	size_t size = strlen(text);
	char path[512];
	snprintf(path, sizeof path, "%s/%s", dir, name);
	FILE *f = fopen(path, "wb");
	assert_non_null(f);
	assert_int_equal(fwrite(text, 1, size, f), size);
	fclose(f);
}

static void load_refused(const char *file, const char *says)
{
	char json[512];
	snprintf(json, sizeof json, "{\"objects\": [{\"mesh\": {\"type\": \"file\", \"path\": \"%s\"}}], \"camera\": "
		 "{\"position\": [0, 0, 5], \"target\": [0, 0, 0]}}", file);
	struct aa_scene *sc = NULL;
	struct aa_error err = {0};
	if (aa_scene_load_string(json, "scene.json", dir, &sc, &err) == 0) {
		aa_scene_free(sc);
		fail_msg("%s loaded", file);
	}
	char named[160];
	snprintf(named, sizeof named, "mesh file '%s'", file);
	if (!strstr(err.message, named) || !strstr(err.message, says) || strcmp(err.path, "objects[0].mesh.path") != 0)
		fail_msg("%s: got %s: %s; wanted '%s'", file, err.path, err.message, says);
}

static void test_through_the_loader(void **state)
{
	(void)state;
	snprintf(dir, sizeof dir, "/tmp/aalab-mesh-text.XXXXXX");
	assert_non_null(mkdtemp(dir));
	/* tests/fuzz/corpus/mesh/crash-off-index-out-of-range without its selector byte */
	static const char crash[] = "OFF\n1 1 0\n0 0 0\n11 0\n0 0 0\n1 0 00\n 01 3 0 1 2\n";
	write_file("crash.off", crash);
	load_refused("crash.off", "line 2: the counts say 1 vertices and 1 faces: a mesh needs at least 3 and 1");
	write_file("wide.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n11 0 1 2 0 1 2 0 1 2 0 1\n");
	load_refused("wide.off", "line 6: face 0 has 11 vertices: OFF faces must have 3 to 9");
	static const char obj[] = "mtllib bad.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
	write_file("bad-mtl.obj", obj);
	write_file("bad.mtl", "newmtl a\nKd 1 x 1\n");
	load_refused("bad-mtl.obj", "material library 'bad.mtl': line 2: Kd: 'x' is not a finite number");
	write_file("mesh.3ds", "MM");
	load_refused("mesh.3ds", "is not in a format aalab reads (glTF 2.0 .gltf or .glb, OBJ .obj, PLY .ply, STL "
				 ".stl, OFF .off)");
	const char *names[] = {"crash.off", "wide.off", "bad-mtl.obj", "bad.mtl", "mesh.3ds"};
	for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
		char path[512];
		snprintf(path, sizeof path, "%s/%s", dir, names[i]);
		unlink(path);
	}
	rmdir(dir);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_cases),
		cmocka_unit_test(test_binary_ply),
		cmocka_unit_test(test_binary_stl),
		cmocka_unit_test(test_long_lines),
		cmocka_unit_test(test_through_the_loader),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
