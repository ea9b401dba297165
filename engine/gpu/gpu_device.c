/* Vulkan instance and device: picks an implementation (lavapipe on CPU machines), enables validation
 * when asked and installed, and counts validation errors so tests can fail on them. */
#include <dirent.h>
#include <dlfcn.h>
#include <link.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "gpu/gpu.h"

double aa_now_ms(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

static VKAPI_ATTR VkBool32 VKAPI_CALL on_debug_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
						       VkDebugUtilsMessageTypeFlagsEXT type,
						       const VkDebugUtilsMessengerCallbackDataEXT *data, void *user)
{
	struct aa_gpu *gpu = user;
	if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) {
		gpu->validation_errors++;
		fprintf(stderr, "aalab: vulkan validation error: %s\n", data->pMessage);
	} else if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) {
		fprintf(stderr, "aalab: vulkan validation warning: %s\n", data->pMessage);
	}
	return VK_FALSE;
}

static bool layer_available(const char *name)
{
	uint32_t n = 0;
	vkEnumerateInstanceLayerProperties(&n, NULL);
	VkLayerProperties *props = calloc(n ? n : 1, sizeof *props);
	vkEnumerateInstanceLayerProperties(&n, props);
	bool found = false;
	for (uint32_t i = 0; i < n; i++)
		found |= strcmp(props[i].layerName, name) == 0;
	free(props);
	return found;
}

static int create_instance(struct aa_gpu *gpu, bool validation, struct aa_error *err)
{
	const char *layers[] = {"VK_LAYER_KHRONOS_validation"};
	const char *exts[] = {VK_EXT_DEBUG_UTILS_EXTENSION_NAME};
	gpu->validation = validation && layer_available(layers[0]);
	VkApplicationInfo app = {
		.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO,
		.pApplicationName = "aalab",
		.pEngineName = "aalab",
		.apiVersion = VK_API_VERSION_1_1,
	};
	VkDebugUtilsMessengerCreateInfoEXT dbg = {
		.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT,
		.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT |
				   VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT,
		.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
			       VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT,
		.pfnUserCallback = on_debug_message,
		.pUserData = gpu,
	};
	VkInstanceCreateInfo ci = {
		.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO,
		.pNext = gpu->validation ? &dbg : NULL,
		.pApplicationInfo = &app,
		.enabledLayerCount = gpu->validation ? 1 : 0,
		.ppEnabledLayerNames = layers,
		.enabledExtensionCount = gpu->validation ? 1 : 0,
		.ppEnabledExtensionNames = exts,
	};
	VkResult vr = vkCreateInstance(&ci, NULL, &gpu->instance);
	if (vr != VK_SUCCESS)
		return aa_error_set(err, AA_ERR_GPU, "", "cannot create a Vulkan instance (VkResult %d): is a "
				    "Vulkan driver installed? On machines without a GPU install mesa-vulkan-drivers",
				    vr);
	if (gpu->validation) {
		PFN_vkCreateDebugUtilsMessengerEXT create = (PFN_vkCreateDebugUtilsMessengerEXT)
			vkGetInstanceProcAddr(gpu->instance, "vkCreateDebugUtilsMessengerEXT");
		if (create)
			create(gpu->instance, &dbg, NULL, &gpu->messenger);
	}
	return 0;
}

static int pick_device(struct aa_gpu *gpu, const char *select, struct aa_error *err)
{
	uint32_t n = 0;
	vkEnumeratePhysicalDevices(gpu->instance, &n, NULL);
	if (n == 0)
		return aa_error_set(err, AA_ERR_GPU, "device", "no Vulkan device found (install "
				    "mesa-vulkan-drivers for the lavapipe CPU implementation)");
	VkPhysicalDevice *devs = calloc(n, sizeof *devs);
	vkEnumeratePhysicalDevices(gpu->instance, &n, devs);
	if (!select || !*select)
		select = getenv("AALAB_DEVICE");
	int chosen = -1;
	char names[1024] = "";
	for (uint32_t i = 0; i < n; i++) {
		VkPhysicalDeviceProperties p;
		vkGetPhysicalDeviceProperties(devs[i], &p);
		size_t len = strlen(names);
		snprintf(names + len, sizeof names - len, "%s%u: %s", i ? ", " : "", i, p.deviceName);
		if (p.apiVersion < VK_API_VERSION_1_1)
			continue;
		if (chosen >= 0)
			continue;
		if (!select || !*select)
			chosen = (int)i;
		else if (strspn(select, "0123456789") == strlen(select) && (uint32_t)atoi(select) == i)
			chosen = (int)i;
		else if (strstr(p.deviceName, select))
			chosen = (int)i;
	}
	if (chosen < 0) {
		free(devs);
		return aa_error_set(err, AA_ERR_GPU, "device", "no Vulkan 1.1 device matches '%s' (devices: %s)",
				    select ? select : "", names);
	}
	gpu->physical = devs[chosen];
	free(devs);
	return 0;
}

static int create_device(struct aa_gpu *gpu, struct aa_error *err)
{
	uint32_t n = 0;
	vkGetPhysicalDeviceQueueFamilyProperties(gpu->physical, &n, NULL);
	VkQueueFamilyProperties *qf = calloc(n ? n : 1, sizeof *qf);
	vkGetPhysicalDeviceQueueFamilyProperties(gpu->physical, &n, qf);
	int family = -1;
	for (uint32_t i = 0; i < n && family < 0; i++)
		if ((qf[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) && (qf[i].queueFlags & VK_QUEUE_COMPUTE_BIT) &&
		    qf[i].timestampValidBits > 0) {
			family = (int)i;
			gpu->timestamp_valid_bits = qf[i].timestampValidBits;
		}
	free(qf);
	if (family < 0)
		return aa_error_set(err, AA_ERR_GPU, "device", "the device has no graphics+compute queue with "
				    "timestamps");
	gpu->queue_family = (uint32_t)family;

	VkPhysicalDeviceFeatures have, want = {0};
	vkGetPhysicalDeviceFeatures(gpu->physical, &have);
	want.shaderSampledImageArrayDynamicIndexing = have.shaderSampledImageArrayDynamicIndexing;
	want.geometryShader = have.geometryShader;
	want.sampleRateShading = have.sampleRateShading;
	want.independentBlend = have.independentBlend;
	want.shaderStorageImageExtendedFormats = have.shaderStorageImageExtendedFormats;
	want.fragmentStoresAndAtomics = have.fragmentStoresAndAtomics;
	want.depthBiasClamp = have.depthBiasClamp;
	float prio = 1.0f;
	VkDeviceQueueCreateInfo qci = {
		.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
		.queueFamilyIndex = gpu->queue_family,
		.queueCount = 1,
		.pQueuePriorities = &prio,
	};
	VkDeviceCreateInfo dci = {
		.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO,
		.queueCreateInfoCount = 1,
		.pQueueCreateInfos = &qci,
		.pEnabledFeatures = &want,
	};
	VkResult vr = vkCreateDevice(gpu->physical, &dci, NULL, &gpu->device);
	if (vr != VK_SUCCESS)
		return aa_error_set(err, AA_ERR_GPU, "device", "vkCreateDevice failed (VkResult %d)", vr);
	vkGetDeviceQueue(gpu->device, gpu->queue_family, 0, &gpu->queue);
	VkCommandPoolCreateInfo pci = {
		.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
		.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT | VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
		.queueFamilyIndex = gpu->queue_family,
	};
	if (vkCreateCommandPool(gpu->device, &pci, NULL, &gpu->command_pool) != VK_SUCCESS)
		return aa_error_set(err, AA_ERR_GPU, "", "vkCreateCommandPool failed");
	return 0;
}

static int create_samplers(struct aa_gpu *gpu, struct aa_error *err)
{
	VkSamplerCreateInfo s = {
		.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO,
		.magFilter = VK_FILTER_NEAREST,
		.minFilter = VK_FILTER_NEAREST,
		.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST,
		.addressModeU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
		.addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
		.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
		.maxLod = 0.0f,
	};
	if (vkCreateSampler(gpu->device, &s, NULL, &gpu->sampler_nearest) != VK_SUCCESS)
		return aa_error_set(err, AA_ERR_GPU, "", "vkCreateSampler failed");
	/* Material textures: trilinear, repeat; mip chains are built on the CPU. */
	s.magFilter = s.minFilter = VK_FILTER_LINEAR;
	s.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
	s.addressModeU = s.addressModeV = s.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
	s.maxLod = VK_LOD_CLAMP_NONE;
	if (vkCreateSampler(gpu->device, &s, NULL, &gpu->sampler_linear) != VK_SUCCESS)
		return aa_error_set(err, AA_ERR_GPU, "", "vkCreateSampler failed");
	/* Post-process passes that filter (SMAA's bilinear taps): linear, clamped, no mips. */
	s.addressModeU = s.addressModeV = s.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
	s.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
	s.maxLod = 0.0f;
	if (vkCreateSampler(gpu->device, &s, NULL, &gpu->sampler_linear_clamp) != VK_SUCCESS)
		return aa_error_set(err, AA_ERR_GPU, "", "vkCreateSampler failed");
	/* Shadow map: hardware 2x2 PCF; reversed-Z, so lit means fragment depth >= stored depth. */
	s.addressModeU = s.addressModeV = s.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER;
	s.borderColor = VK_BORDER_COLOR_FLOAT_OPAQUE_BLACK;
	s.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
	s.maxLod = 0.0f;
	s.compareEnable = VK_TRUE;
	s.compareOp = VK_COMPARE_OP_GREATER_OR_EQUAL;
	if (vkCreateSampler(gpu->device, &s, NULL, &gpu->sampler_shadow) != VK_SUCCESS)
		return aa_error_set(err, AA_ERR_GPU, "", "vkCreateSampler failed");
	return 0;
}

#if defined(__SANITIZE_ADDRESS__)
/* The loader dlcloses the driver and layers when the instance goes; LeakSanitizer then cannot name the
 * library behind a driver-internal allocation, and suppressions cannot match it. Pinning every loaded
 * library (RTLD_NOLOAD | RTLD_NODELETE) keeps their names for the leak report. Sanitizer builds only. */
static int pin_library(struct dl_phdr_info *info, size_t size, void *data)
{
	(void)size;
	(void)data;
	if (info->dlpi_name && info->dlpi_name[0])
		(void)dlopen(info->dlpi_name, RTLD_LAZY | RTLD_NOLOAD | RTLD_NODELETE);
	return 0;
}
#endif

#if defined(__SANITIZE_ADDRESS__)
/* The loader also opens every installed driver (ICD) while it enumerates them, and closes them before
 * the device exists; what a driver allocates at load time then leaks from an unmapped library that no
 * suppression can name. Opening the drivers first, never to be closed, keeps them mapped. The library
 * path of each ICD manifest in the standard folders. Sanitizer builds only. */
static void pin_drivers(void)
{
	static const char *const dirs[] = {"/usr/share/vulkan/icd.d", "/etc/vulkan/icd.d"};
	for (size_t d = 0; d < sizeof dirs / sizeof dirs[0]; d++) {
		DIR *dir = opendir(dirs[d]);
		struct dirent *e;
		while (dir && (e = readdir(dir))) {
			char path[1024], text[4096], library[1024];
			if (!strstr(e->d_name, ".json") ||
			    (size_t)snprintf(path, sizeof path, "%s/%s", dirs[d], e->d_name) >= sizeof path)
				continue;
			FILE *f = fopen(path, "r");
			size_t n = f ? fread(text, 1, sizeof text - 1, f) : 0;
			if (f)
				fclose(f);
			text[n] = '\0';
			/* a space in a scanf format matches any white space, none included */
			const char *key = strstr(text, "\"library_path\"");
			if (key && sscanf(key, "\"library_path\" : \"%1023[^\"]\"", library) == 1)
				(void)dlopen(library, RTLD_LAZY | RTLD_NODELETE);
		}
		if (dir)
			closedir(dir);
	}
}
#endif

int aa_gpu_create(struct aa_gpu *gpu, const char *device_select, bool validation, struct aa_error *err)
{
	memset(gpu, 0, sizeof *gpu);
#if defined(__SANITIZE_ADDRESS__)
	pin_drivers();
#endif
	if (create_instance(gpu, validation, err) || pick_device(gpu, device_select, err) ||
	    create_device(gpu, err) || create_samplers(gpu, err)) {
		aa_gpu_destroy(gpu);
		return -1;
	}
#if defined(__SANITIZE_ADDRESS__)
	dl_iterate_phdr(pin_library, NULL);
#endif
	vkGetPhysicalDeviceProperties(gpu->physical, &gpu->properties);
	vkGetPhysicalDeviceMemoryProperties(gpu->physical, &gpu->memory_properties);
	gpu->timestamp_period_ns = gpu->properties.limits.timestampPeriod;
	gpu->color_sample_counts = gpu->properties.limits.framebufferColorSampleCounts &
				   gpu->properties.limits.framebufferDepthSampleCounts;
	/* the driver's own name and build (Vulkan 1.2): what stored references are keyed by besides the ids */
	if (gpu->properties.apiVersion >= VK_API_VERSION_1_2) {
		VkPhysicalDeviceDriverProperties driver = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
		VkPhysicalDeviceProperties2 p2 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, .pNext = &driver};
		vkGetPhysicalDeviceProperties2(gpu->physical, &p2);
		snprintf(gpu->driver_build, sizeof gpu->driver_build, "%.120s %.120s", driver.driverName,
			 driver.driverInfo);
	}
	uint32_t v = gpu->properties.driverVersion, api = gpu->properties.apiVersion;
	snprintf(gpu->driver_info, sizeof gpu->driver_info, "Vulkan %u.%u.%u, driver 0x%x%s",
		 VK_API_VERSION_MAJOR(api), VK_API_VERSION_MINOR(api), VK_API_VERSION_PATCH(api), v,
		 gpu->validation ? ", validation on" : "");
	return 0;
}

void aa_gpu_destroy(struct aa_gpu *gpu)
{
	if (gpu->device) {
		vkDeviceWaitIdle(gpu->device);
		vkDestroySampler(gpu->device, gpu->sampler_nearest, NULL);
		vkDestroySampler(gpu->device, gpu->sampler_linear, NULL);
		vkDestroySampler(gpu->device, gpu->sampler_linear_clamp, NULL);
		vkDestroySampler(gpu->device, gpu->sampler_shadow, NULL);
		vkDestroyCommandPool(gpu->device, gpu->command_pool, NULL);
		vkDestroyDevice(gpu->device, NULL);
	}
	if (gpu->messenger) {
		PFN_vkDestroyDebugUtilsMessengerEXT destroy = (PFN_vkDestroyDebugUtilsMessengerEXT)
			vkGetInstanceProcAddr(gpu->instance, "vkDestroyDebugUtilsMessengerEXT");
		if (destroy)
			destroy(gpu->instance, gpu->messenger, NULL);
	}
	if (gpu->instance)
		vkDestroyInstance(gpu->instance, NULL);
	int errors = gpu->validation_errors;
	memset(gpu, 0, sizeof *gpu);
	gpu->validation_errors = errors;
}
