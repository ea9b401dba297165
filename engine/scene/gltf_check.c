/* A glTF file read by aalab itself before assimp sees it: the .glb container and the JSON, the refusal
 * rules assimp 5.2 does not apply (it loads unknown required extensions, drops triangles with indices past
 * the vertices, crashes on glTF 1.0, says "No suitable reader found" for a truncated .glb or a .gltf that
 * is not JSON), the warnings for what aalab drops, and the extension data assimp does not carry
 * (KHR_materials_emissive_strength, KHR_texture_transform per texture). */
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "scene/mesh_file.h"
#include "util/file_open.h"

#define GLB_MAGIC 0x46546C67u      /* "glTF" */
#define GLB_CHUNK_JSON 0x4E4F534Au /* "JSON" */
#define GLB_CHUNK_BIN 0x004E4942u  /* "BIN\0" */

/* Extensions aalab draws as the specification says; a file that requires any other is refused. */
static const char *const supported_extensions[] = {"KHR_materials_emissive_strength", "KHR_texture_transform",
						   "KHR_materials_unlit", NULL};

static bool ends_with(const char *s, const char *suffix)
{
	size_t a = strlen(s), b = strlen(suffix);
	return a >= b && strcasecmp(s + a - b, suffix) == 0;
}

bool aa_gltf_file_is_gltf(const char *path)
{
	if (ends_with(path, ".gltf") || ends_with(path, ".glb"))
		return true;
	unsigned char magic[4] = {0};
	FILE *f = aa_file_fopen_regular(path, "", NULL); /* never blocks on a FIFO */
	bool glb = f && fread(magic, 1, 4, f) == 4 && memcmp(magic, "glTF", 4) == 0;
	if (f)
		fclose(f);
	return glb;
}

static int hex_value(char c)
{
	return c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
}

int aa_resolve_beside(const char *model_path, const char *base_dir, const char *uri, char *out, size_t size,
		      struct aa_error *err)
{
	char rel[1024], joined[PATH_MAX], real_base[PATH_MAX], real_file[PATH_MAX];
	size_t n = 0;
	for (const char *p = uri; *p && n + 1 < sizeof rel; p++) { /* glTF URIs escape spaces and the like */
		if (p[0] == '%' && hex_value(p[1]) >= 0 && hex_value(p[2]) >= 0) {
			rel[n++] = (char)(hex_value(p[1]) * 16 + hex_value(p[2]));
			p += 2;
		} else {
			rel[n++] = *p == '\\' ? '/' : *p;
		}
	}
	rel[n] = '\0';
	if (!rel[0] || strlen(uri) >= sizeof rel)
		return aa_error_set(err, AA_ERR_INVALID, "", "'%.200s' is not a usable file name", uri);
	if (rel[0] == '/' || strstr(rel, "://"))
		return aa_error_set(err, AA_ERR_INVALID, "", "'%.200s' is not a relative path: files a mesh names must "
				    "be beside it, inside the scene's directory", uri);
	for (const char *p = rel; *p;) {
		size_t len = strcspn(p, "/");
		if (len == 2 && p[0] == '.' && p[1] == '.')
			return aa_error_set(err, AA_ERR_INVALID, "", "'..' is not allowed in '%.200s': files must stay in "
					    "the scene's directory", uri);
		p += len + (p[len] == '/');
	}
	const char *slash = strrchr(model_path, '/');
	int dir_len = slash ? (int)(slash - model_path) : 1;
	int w = snprintf(joined, sizeof joined, "%.*s/%s", dir_len, slash ? model_path : ".", rel);
	if (w < 0 || (size_t)w >= sizeof joined)
		return aa_error_set(err, AA_ERR_INVALID, "", "path too long: '%.200s'", uri);
	if (!realpath(joined, real_file))
		return aa_error_set(err, AA_ERR_NOT_FOUND, "", "'%.200s' not found", rel);
	if (base_dir && realpath(base_dir, real_base)) {
		size_t bl = strlen(real_base);
		if (strncmp(real_file, real_base, bl) != 0 || (real_file[bl] != '/' && strcmp(real_base, "/") != 0))
			return aa_error_set(err, AA_ERR_INVALID, "", "'%.200s' resolves outside the scene's directory", rel);
	}
	if (strlen(real_file) >= size)
		return aa_error_set(err, AA_ERR_INVALID, "", "path too long: '%.200s'", uri);
	memcpy(out, real_file, strlen(real_file) + 1);
	aa_scene_source_read(out);
	return 0;
}

/* ---------------------------------------------------------------- the document and its buffers */

struct buffer {
	uint8_t *data; /* owned unless it points into the .glb */
	size_t size;
	bool owned;
};

struct doc {
	struct sj *s;
	struct aa_scene *scene;
	const char *shown, *path, *base_dir;
	json_t *root;
	uint8_t *file;
	size_t file_size;
	const uint8_t *bin; /* the .glb BIN chunk */
	size_t bin_size;
	struct buffer *buffers;
	int buffer_count;
};

/* Errors: "mesh file 'x.glb': <what>" at the scene's current path. */
#define FAIL(d, code, ...) fail_doc((d), (code), __VA_ARGS__)
__attribute__((format(printf, 3, 4))) static int fail_doc(struct doc *d, enum aa_error_code code, const char *fmt, ...)
{
	char msg[600];
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(msg, sizeof msg, fmt, ap);
	va_end(ap);
	return sj_fail(d->s, code, "mesh file '%s': %s", d->shown, msg);
}

static int read_file(struct doc *d)
{
	struct aa_error oe = {0};
	FILE *f = aa_file_fopen_regular(d->path, "", &oe); /* never blocks on a FIFO */
	struct stat st;
	if (!f || fstat(fileno(f), &st) != 0) {
		if (f)
			fclose(f);
		if (oe.code == AA_ERR_INVALID)
			return FAIL(d, AA_ERR_INVALID, "is not a regular file (a FIFO, socket or device)");
		return FAIL(d, AA_ERR_IO, "cannot open: %s", strerror(errno));
	}
	d->file_size = (size_t)st.st_size;
	d->file = malloc(d->file_size + 1);
	size_t got = d->file ? fread(d->file, 1, d->file_size, f) : 0;
	fclose(f);
	if (!d->file || got != d->file_size)
		return FAIL(d, AA_ERR_IO, "cannot read it");
	d->file[d->file_size] = 0;
	return 0;
}

static uint32_t le32(const uint8_t *p)
{
	return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

/* The container: a .glb's header and chunks (its JSON and BIN), or the whole file as JSON text. */
static int parse_container(struct doc *d)
{
	const uint8_t *json_text = d->file;
	size_t json_size = d->file_size;
	bool magic = d->file_size >= 4 && le32(d->file) == GLB_MAGIC;
	if (ends_with(d->path, ".glb") && !magic)
		return FAIL(d, AA_ERR_INVALID, "not a binary glTF file: a .glb starts with the bytes 'glTF'");
	if (magic) {
		if (d->file_size < 20)
			return FAIL(d, AA_ERR_INVALID, "truncated: %zu bytes, shorter than a .glb header", d->file_size);
		uint32_t version = le32(d->file + 4), length = le32(d->file + 8);
		if (version == 1)
			return FAIL(d, AA_ERR_INVALID, "is binary glTF 1.0, which aalab does not read: convert it to glTF "
				    "2.0 (for example with gltf-pipeline or Blender)");
		if (version != 2)
			return FAIL(d, AA_ERR_INVALID, "is binary glTF version %u; aalab reads glTF 2.0", version);
		if (length > d->file_size)
			return FAIL(d, AA_ERR_INVALID, "truncated: its header says %u bytes, the file has %zu", length,
				    d->file_size);
		uint32_t chunk_length = le32(d->file + 12), chunk_type = le32(d->file + 16);
		if (chunk_type != GLB_CHUNK_JSON)
			return FAIL(d, AA_ERR_INVALID, "malformed .glb: its first chunk is not JSON");
		if ((uint64_t)chunk_length + 20 > length)
			return FAIL(d, AA_ERR_INVALID, "truncated: its JSON chunk of %u bytes runs past the end (%u bytes)",
				    chunk_length, length);
		json_text = d->file + 20;
		json_size = chunk_length;
		size_t next = 20 + (size_t)chunk_length;
		if (next + 8 <= length) {
			uint32_t bin_length = le32(d->file + next), bin_type = le32(d->file + next + 4);
			if (bin_type == GLB_CHUNK_BIN) {
				if ((uint64_t)next + 8 + bin_length > length)
					return FAIL(d, AA_ERR_INVALID, "truncated: its BIN chunk of %u bytes runs past the end "
						    "(%u bytes)", bin_length, length);
				d->bin = d->file + next + 8;
				d->bin_size = bin_length;
			}
		}
	}
	json_error_t je;
	d->root = json_loadb((const char *)json_text, json_size, JSON_REJECT_DUPLICATES, &je);
	if (!d->root)
		return FAIL(d, AA_ERR_INVALID, "is not glTF: %s at line %d, column %d (a .gltf file is JSON text)",
			    je.text, je.line, je.column);
	if (!json_is_object(d->root))
		return FAIL(d, AA_ERR_INVALID, "is not glTF: its JSON is not an object");
	return 0;
}

static const char *string_at(const json_t *o, const char *key)
{
	const json_t *v = json_object_get(o, key);
	return json_is_string(v) ? json_string_value(v) : NULL;
}

static bool in_list(const char *const *list, const char *name)
{
	for (int i = 0; list[i]; i++)
		if (strcmp(list[i], name) == 0)
			return true;
	return false;
}

/* asset.version 2.x, extensionsRequired all supported, extensionsUsed others warned about. */
static int check_version_and_extensions(struct doc *d)
{
	const json_t *asset = json_object_get(d->root, "asset");
	const char *version = string_at(asset, "version");
	if (!version)
		return FAIL(d, AA_ERR_INVALID, "has no asset.version: not a glTF 2.0 file");
	if (version[0] == '1' && (version[1] == '.' || !version[1]))
		return FAIL(d, AA_ERR_INVALID, "is glTF %s (asset.version), which aalab does not read: convert it to "
			    "glTF 2.0 (for example with gltf-pipeline or Blender)", version);
	if (version[0] != '2' || (version[1] && version[1] != '.'))
		return FAIL(d, AA_ERR_INVALID, "is glTF %s (asset.version); aalab reads glTF 2.0", version);
	const char *min_version = string_at(asset, "minVersion");
	if (min_version && strcmp(min_version, "2.0") != 0)
		return FAIL(d, AA_ERR_INVALID, "needs a glTF reader of version %s (asset.minVersion); aalab reads 2.0",
			    min_version);
	char list[200] = "";
	for (int i = 0; supported_extensions[i]; i++)
		snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", i ? ", " : "", supported_extensions[i]);
	const json_t *required = json_object_get(d->root, "extensionsRequired");
	size_t i;
	const json_t *e;
	json_array_foreach(required, i, e) {
		if (!json_is_string(e))
			return FAIL(d, AA_ERR_INVALID, "extensionsRequired[%zu] is not a string", i);
		if (!in_list(supported_extensions, json_string_value(e)))
			return FAIL(d, AA_ERR_INVALID, "requires the extension %s (extensionsRequired[%zu]), which aalab does "
				    "not support (it supports %s)", json_string_value(e), i, list);
	}
	json_array_foreach(json_object_get(d->root, "extensionsUsed"), i, e)
		if (json_is_string(e) && !in_list(supported_extensions, json_string_value(e)))
			aa_scene_warn(d->scene, "%s: uses the extension %s, which aalab ignores (drawn without it)",
				      d->shown, json_string_value(e));
	return 0;
}

static const char *b64_alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

/* Decodes base64 (whitespace and padding tolerated); NULL on a bad character. */
static uint8_t *base64_decode(const char *text, size_t *out_size)
{
	size_t len = strlen(text), n = 0;
	uint8_t *out = malloc(len / 4 * 3 + 3);
	uint32_t acc = 0;
	int bits = 0;
	if (!out)
		return NULL;
	for (size_t i = 0; i < len; i++) {
		char c = text[i];
		if (c == '=' || c == ' ' || c == '\n' || c == '\r')
			continue;
		const char *p = strchr(b64_alphabet, c);
		if (!p || !c) {
			free(out);
			return NULL;
		}
		acc = acc << 6 | (uint32_t)(p - b64_alphabet);
		bits += 6;
		if (bits >= 8) {
			bits -= 8;
			out[n++] = (uint8_t)(acc >> bits);
		}
	}
	*out_size = n;
	return out;
}

/* Every buffer's bytes: the .glb BIN chunk, a data URI or a file beside the glTF. */
static int load_buffers(struct doc *d)
{
	const json_t *buffers = json_object_get(d->root, "buffers");
	d->buffer_count = (int)json_array_size(buffers);
	if (!d->buffer_count)
		return 0;
	if (!(d->buffers = calloc((size_t)d->buffer_count, sizeof *d->buffers)))
		return FAIL(d, AA_ERR_INTERNAL, "out of memory");
	for (int i = 0; i < d->buffer_count; i++) {
		const json_t *b = json_array_get(buffers, (size_t)i);
		const char *uri = string_at(b, "uri");
		json_int_t declared = json_integer_value(json_object_get(b, "byteLength"));
		struct buffer *out = &d->buffers[i];
		if (!uri) {
			if (i != 0 || !d->bin)
				return FAIL(d, AA_ERR_INVALID, "buffers[%d] has no uri and no .glb BIN chunk holds it", i);
			out->data = (uint8_t *)d->bin;
			out->size = d->bin_size;
		} else if (strncmp(uri, "data:", 5) == 0) {
			const char *comma = strchr(uri, ',');
			if (!comma || !strstr(uri, ";base64,"))
				return FAIL(d, AA_ERR_INVALID, "buffers[%d].uri is a data URI without base64 data", i);
			if (!(out->data = base64_decode(comma + 1, &out->size)))
				return FAIL(d, AA_ERR_INVALID, "buffers[%d].uri: the base64 data is malformed", i);
			out->owned = true;
		} else {
			char full[PATH_MAX];
			struct aa_error e = {0};
			if (aa_resolve_beside(d->path, d->base_dir, uri, full, sizeof full, &e))
				return FAIL(d, e.code, "buffers[%d].uri: %s", i, e.message);
			struct stat st;
			FILE *f = aa_file_fopen_regular(full, "", &e); /* never blocks on a FIFO */
			if (!f && e.code == AA_ERR_INVALID)
				return FAIL(d, AA_ERR_INVALID, "buffers[%d].uri: '%s' is not a regular file (a FIFO, socket or device)", i, uri);
			if (!f || fstat(fileno(f), &st) != 0 || (uint64_t)st.st_size > AA_MESH_FILE_MAX_BYTES) {
				if (f)
					fclose(f);
				return FAIL(d, AA_ERR_LIMIT, "buffers[%d].uri: '%s' cannot be read or is over %u bytes", i,
					    uri, (unsigned)AA_MESH_FILE_MAX_BYTES);
			}
			out->size = (size_t)st.st_size;
			out->data = malloc(out->size ? out->size : 1);
			out->owned = true;
			size_t got = out->data ? fread(out->data, 1, out->size, f) : 0;
			fclose(f);
			if (!out->data || got != out->size)
				return FAIL(d, AA_ERR_IO, "buffers[%d].uri: cannot read '%s'", i, uri);
		}
		if (declared < 0 || (uint64_t)declared > out->size)
			return FAIL(d, AA_ERR_INVALID, "buffers[%d] is %zu bytes, but its byteLength says %lld (truncated?)", i,
				    out->size, (long long)declared);
		out->size = (size_t)declared;
	}
	return 0;
}

static int component_bytes(json_int_t type)
{
	switch (type) {
	case 5120: case 5121: return 1;
	case 5122: case 5123: return 2;
	case 5125: case 5126: return 4;
	}
	return 0;
}

static int type_components(const char *type)
{
	static const char *const names[] = {"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"};
	static const int counts[] = {1, 2, 3, 4, 4, 9, 16};
	for (int i = 0; type && i < 7; i++)
		if (strcmp(type, names[i]) == 0)
			return counts[i];
	return 0;
}

struct accessor {
	const uint8_t *data; /* first element; NULL when the accessor has no bufferView (all zeros) */
	size_t count, stride;
	json_int_t component;
	int components;
	bool sparse;
};

/* An accessor checked against its buffer view and buffer: every element it reads lies inside them. */
static int accessor_at(struct doc *d, json_int_t index, struct accessor *a)
{
	const json_t *accessors = json_object_get(d->root, "accessors");
	const json_t *acc = json_array_get(accessors, (size_t)index);
	memset(a, 0, sizeof *a);
	if (index < 0 || !json_is_object(acc))
		return FAIL(d, AA_ERR_INVALID, "accessor %lld does not exist (the file has %zu)", (long long)index,
			    json_array_size(accessors));
	a->count = (size_t)json_integer_value(json_object_get(acc, "count"));
	a->component = json_integer_value(json_object_get(acc, "componentType"));
	a->components = type_components(string_at(acc, "type"));
	a->sparse = json_object_get(acc, "sparse") != NULL;
	int cb = component_bytes(a->component);
	if (!cb || !a->components || json_integer_value(json_object_get(acc, "count")) < 1)
		return FAIL(d, AA_ERR_INVALID, "accessors[%lld] has a bad count, componentType or type", (long long)index);
	const json_t *view_index = json_object_get(acc, "bufferView");
	if (!view_index)
		return 0;
	const json_t *view = json_array_get(json_object_get(d->root, "bufferViews"),
					    (size_t)json_integer_value(view_index));
	json_int_t buffer = json_integer_value(json_object_get(view, "buffer"));
	if (!json_is_object(view) || buffer < 0 || buffer >= d->buffer_count)
		return FAIL(d, AA_ERR_INVALID, "accessors[%lld].bufferView names no buffer view with a buffer",
			    (long long)index);
	uint64_t view_offset = (uint64_t)json_integer_value(json_object_get(view, "byteOffset"));
	uint64_t view_length = (uint64_t)json_integer_value(json_object_get(view, "byteLength"));
	uint64_t offset = (uint64_t)json_integer_value(json_object_get(acc, "byteOffset"));
	uint64_t element = (uint64_t)cb * (uint64_t)a->components;
	uint64_t stride = (uint64_t)json_integer_value(json_object_get(view, "byteStride"));
	a->stride = stride ? (size_t)stride : (size_t)element;
	if (view_offset + view_length > d->buffers[buffer].size)
		return FAIL(d, AA_ERR_INVALID, "bufferViews[%lld] runs past the end of buffers[%lld] (%llu + %llu > %zu "
			    "bytes)", (long long)json_integer_value(view_index), (long long)buffer,
			    (unsigned long long)view_offset, (unsigned long long)view_length, d->buffers[buffer].size);
	if (offset + (uint64_t)a->stride * (a->count - 1) + element > view_length)
		return FAIL(d, AA_ERR_INVALID, "accessors[%lld] reads past the end of bufferViews[%lld] (%zu elements of "
			    "%llu bytes)", (long long)index, (long long)json_integer_value(view_index), a->count,
			    (unsigned long long)element);
	a->data = d->buffers[buffer].data + view_offset + offset;
	return 0;
}

static uint64_t index_value(const struct accessor *a, size_t i)
{
	const uint8_t *p = a->data + i * a->stride;
	return a->component == 5121 ? p[0] : a->component == 5123 ? (uint64_t)(p[0] | p[1] << 8) : le32(p);
}

/* Primitives: no morph targets; attributes of one length; every index names a vertex. */
static int check_meshes(struct doc *d)
{
	size_t m, p;
	const json_t *mesh, *prim;
	json_array_foreach(json_object_get(d->root, "meshes"), m, mesh) {
		json_array_foreach(json_object_get(mesh, "primitives"), p, prim) {
			if (json_array_size(json_object_get(prim, "targets")) > 0)
				return FAIL(d, AA_ERR_INVALID, "meshes[%zu].primitives[%zu] has morph targets, which aalab does "
					    "not support (remove them, or bake the shape you want)", m, p);
			const json_t *attributes = json_object_get(prim, "attributes");
			const json_t *position = json_object_get(attributes, "POSITION");
			if (!position)
				return FAIL(d, AA_ERR_INVALID, "meshes[%zu].primitives[%zu] has no POSITION attribute", m, p);
			struct accessor a;
			if (accessor_at(d, json_integer_value(position), &a))
				return -1;
			size_t vertices = a.count;
			const char *name;
			const json_t *value;
			json_object_foreach((json_t *)attributes, name, value) {
				if (accessor_at(d, json_integer_value(value), &a))
					return -1;
				if (a.count != vertices)
					return FAIL(d, AA_ERR_INVALID, "meshes[%zu].primitives[%zu].attributes.%s has %zu elements, "
						    "POSITION has %zu", m, p, name, a.count, vertices);
			}
			json_int_t mode = json_object_get(prim, "mode") ? json_integer_value(json_object_get(prim, "mode")) : 4;
			if (mode < 4)
				aa_scene_warn(d->scene, "%s: meshes[%zu].primitives[%zu] draws %s, which have no area: not drawn",
					      d->shown, m, p, mode == 0 ? "points" : "lines");
			const json_t *indices = json_object_get(prim, "indices");
			if (!indices)
				continue;
			if (accessor_at(d, json_integer_value(indices), &a))
				return -1;
			if ((a.component != 5121 && a.component != 5123 && a.component != 5125) || a.components != 1)
				return FAIL(d, AA_ERR_INVALID, "meshes[%zu].primitives[%zu].indices: indices are unsigned "
					    "integer scalars", m, p);
			for (size_t i = 0; a.data && !a.sparse && i < a.count; i++) {
				uint64_t v = index_value(&a, i);
				if (v >= vertices)
					return FAIL(d, AA_ERR_INVALID, "meshes[%zu].primitives[%zu].indices: index %llu (element %zu) "
						    "is out of range: the primitive has %zu vertices", m, p, (unsigned long long)v, i,
						    vertices);
			}
		}
	}
	return 0;
}

/* A texture reference's texCoord and KHR_texture_transform. */
static int read_map(struct doc *d, const json_t *ref, size_t material, const char *field, struct aa_gltf_map *map)
{
	map->scale[0] = map->scale[1] = 1.0f;
	if (!json_is_object(ref))
		return 0;
	map->present = true;
	map->tex_coord = (int)json_integer_value(json_object_get(ref, "texCoord"));
	const json_t *xf = json_object_get(json_object_get(ref, "extensions"), "KHR_texture_transform");
	if (json_is_object(xf)) {
		const json_t *offset = json_object_get(xf, "offset"), *scale = json_object_get(xf, "scale");
		double v[5] = {0, 0, 0, 1, 1};
		if (offset)
			v[0] = json_number_value(json_array_get(offset, 0)), v[1] = json_number_value(json_array_get(offset, 1));
		if (json_object_get(xf, "rotation"))
			v[2] = json_number_value(json_object_get(xf, "rotation"));
		if (scale)
			v[3] = json_number_value(json_array_get(scale, 0)), v[4] = json_number_value(json_array_get(scale, 1));
		for (int k = 0; k < 5; k++)
			if (!isfinite(v[k]) || fabs(v[k]) > 1e7)
				return FAIL(d, AA_ERR_INVALID, "materials[%zu].%s: KHR_texture_transform has a value that is not a "
					    "finite number within 1e7", material, field);
		map->transformed = true;
		map->offset[0] = (float)v[0], map->offset[1] = (float)v[1];
		map->rotation = (float)v[2];
		map->scale[0] = (float)v[3], map->scale[1] = (float)v[4];
		if (json_object_get(xf, "texCoord"))
			map->tex_coord = (int)json_integer_value(json_object_get(xf, "texCoord"));
	}
	return 0;
}

static int read_materials(struct doc *d, struct aa_gltf_info *info)
{
	const json_t *materials = json_object_get(d->root, "materials");
	info->material_count = (int)json_array_size(materials);
	if (!info->material_count)
		return 0;
	if (!(info->materials = calloc((size_t)info->material_count, sizeof *info->materials)))
		return FAIL(d, AA_ERR_INTERNAL, "out of memory");
	static const char *const map_names[AA_MAP_COUNT] = {"baseColorTexture", "emissiveTexture", "normalTexture",
							     "metallicRoughnessTexture", "occlusionTexture"};
	size_t i;
	const json_t *mat;
	json_array_foreach(materials, i, mat) {
		struct aa_gltf_material *out = &info->materials[i];
		const json_t *pbr = json_object_get(mat, "pbrMetallicRoughness");
		const json_t *refs[AA_MAP_COUNT] = {
			json_object_get(pbr, "baseColorTexture"), json_object_get(mat, "emissiveTexture"),
			json_object_get(mat, "normalTexture"), json_object_get(pbr, "metallicRoughnessTexture"),
			json_object_get(mat, "occlusionTexture")};
		const char *name = string_at(mat, "name");
		for (int k = 0; k < AA_MAP_COUNT; k++) {
			if (read_map(d, refs[k], i, map_names[k], &out->maps[k]))
				return -1;
			if (out->maps[k].present && out->maps[k].tex_coord != 0)
				aa_scene_warn(d->scene, "%s: materials[%zu] '%s': %s reads TEXCOORD_%d; aalab draws it with "
					      "TEXCOORD_0", d->shown, i, name ? name : "", map_names[k], out->maps[k].tex_coord);
		}
		out->emissive_strength = 1.0f;
		const json_t *strength = json_object_get(json_object_get(json_object_get(mat, "extensions"),
									 "KHR_materials_emissive_strength"), "emissiveStrength");
		if (strength) {
			double v = json_number_value(strength);
			if (!json_is_number(strength) || !isfinite(v) || v < 0 || v > 1e7)
				return FAIL(d, AA_ERR_INVALID, "materials[%zu]: KHR_materials_emissive_strength.emissiveStrength "
					    "must be a number in [0, 1e7]", i);
			out->emissive_strength = (float)v;
		}
		if (json_object_get(json_object_get(mat, "extensions"), "KHR_materials_pbrSpecularGlossiness"))
			aa_scene_warn(d->scene, "%s: materials[%zu] '%s' is specular-glossiness: drawn as metallic-roughness "
				      "from its diffuse colour (approximated)", d->shown, i, name ? name : "");
	}
	return 0;
}

/* What aalab draws differently from the file: sampler wrap and filter modes, animation interpolation. */
static void warn_approximations(struct doc *d)
{
	size_t i;
	const json_t *v;
	json_array_foreach(json_object_get(d->root, "samplers"), i, v) {
		json_int_t wrap_s = json_object_get(v, "wrapS") ? json_integer_value(json_object_get(v, "wrapS")) : 10497;
		json_int_t wrap_t = json_object_get(v, "wrapT") ? json_integer_value(json_object_get(v, "wrapT")) : 10497;
		if (wrap_s != 10497 || wrap_t != 10497)
			aa_scene_warn(d->scene, "%s: samplers[%zu] clamps or mirrors; aalab repeats every texture", d->shown, i);
		if (json_integer_value(json_object_get(v, "magFilter")) == 9728)
			aa_scene_warn(d->scene, "%s: samplers[%zu] asks for NEAREST magnification; aalab filters every "
				      "texture linearly (trilinear)", d->shown, i);
	}
	json_array_foreach(json_object_get(d->root, "animations"), i, v) {
		size_t k;
		const json_t *sampler;
		json_array_foreach(json_object_get(v, "samplers"), k, sampler) {
			const char *mode = string_at(sampler, "interpolation");
			if (mode && strcmp(mode, "LINEAR") != 0) {
				const char *name = string_at(v, "name");
				aa_scene_warn(d->scene, "%s: animations[%zu] '%s' has %s keys; aalab interpolates them linearly",
					      d->shown, i, name ? name : "", mode);
				break;
			}
		}
	}
}

void aa_gltf_info_free(struct aa_gltf_info *info)
{
	free(info->materials);
	memset(info, 0, sizeof *info);
}

int aa_gltf_check(struct sj *s, struct aa_scene *scene, const char *path, const char *shown, const char *base_dir,
		  struct aa_gltf_info *info)
{
	struct doc d = {.s = s, .scene = scene, .shown = shown, .path = path, .base_dir = base_dir};
	memset(info, 0, sizeof *info);
	int rc = read_file(&d) || parse_container(&d) || check_version_and_extensions(&d) || load_buffers(&d) ||
		 check_meshes(&d) || read_materials(&d, info);
	if (rc == 0)
		warn_approximations(&d);
	for (int i = 0; i < d.buffer_count; i++)
		if (d.buffers[i].owned)
			free(d.buffers[i].data);
	free(d.buffers);
	json_decref(d.root);
	free(d.file);
	if (rc)
		aa_gltf_info_free(info);
	return rc ? -1 : 0;
}
