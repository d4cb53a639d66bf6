// Builds a scene from its description (the schema of tests/three_js/scene.json), renders it
// once with three.js's WebGLRenderer into a float render target, and reads the pixels back.
//
// render(description) returns { revision, width, height, pixels }: pixels is the base64 of
// the render target's floats, RGBA, width * height * 4 of them in the platform's byte order,
// rows bottom to top as WebGL reads them. A render target takes the shaders' linear output:
// no tone mapping, no sRGB encoding. Throws on a description it does not understand, on a
// browser without WebGL2 or EXT_color_buffer_float, and when the read-back fails.
import * as THREE from "three";

// Each geometry's constructor arguments in order; the rest keep three.js's defaults.
const GEOMETRY_ARGUMENTS = {
  PlaneGeometry: ["width", "height"],
  SphereGeometry: ["radius", "widthSegments", "heightSegments"],
  BoxGeometry: ["width", "height", "depth"],
};
const LIGHT_TYPES = [
  "AmbientLight",
  "HemisphereLight",
  "DirectionalLight",
  "PointLight",
  "SpotLight",
];
const MATERIAL_TYPES = ["MeshPhongMaterial", "MeshToonMaterial"];

function vector(value, what) {
  if (!Array.isArray(value) || value.length !== 3 || !value.every(Number.isFinite)) {
    throw new Error(`${what} is not three numbers: ${JSON.stringify(value)}`);
  }
  return new THREE.Vector3(...value);
}

// Sets the object's properties named in `settings`, which must exist on it. A number given
// for a Color property is an sRGB hex, as toJSON writes it: THREE.Color converts it to
// linear (ColorManagement is on).
function assign(object, settings, what) {
  for (const [key, value] of Object.entries(settings)) {
    if (!(key in object)) throw new Error(`${what} has no property ${key}`);
    if (object[key] !== null && object[key].isColor) object[key] = new THREE.Color(value);
    else if (typeof object[key] === "number" && typeof value === "number") object[key] = value;
    else throw new Error(`${what}.${key} cannot be set to ${JSON.stringify(value)}`);
  }
}

function makeLight(scene, description) {
  const { type, position, target, ...settings } = description;
  if (!LIGHT_TYPES.includes(type)) throw new Error(`unknown light type ${type}`);
  const light = new THREE[type]();
  assign(light, settings, type);
  if (position !== undefined) light.position.copy(vector(position, `${type}.position`));
  if (target !== undefined) {
    if (light.target === undefined) throw new Error(`${type} has no target`);
    light.target.position.copy(vector(target, `${type}.target`));
    scene.add(light.target);
    light.target.updateMatrixWorld();
  }
  light.castShadow = false;
  scene.add(light);
}

// A toon gradient map from its bytes: one row, red channel, nearest filtering, linear
// (NoColorSpace), no mipmaps.
function gradientMap(bytes) {
  const texture = new THREE.DataTexture(
    new Uint8Array(bytes),
    bytes.length,
    1,
    THREE.RedFormat,
    THREE.UnsignedByteType,
  );
  texture.minFilter = THREE.NearestFilter;
  texture.magFilter = THREE.NearestFilter;
  texture.generateMipmaps = false;
  texture.needsUpdate = true;
  return texture;
}

function makeMaterial(name, description) {
  const { type, gradientMap: gradient, ...settings } = description;
  if (!MATERIAL_TYPES.includes(type)) throw new Error(`material ${name}: unknown type ${type}`);
  const material = new THREE[type]();
  assign(material, settings, `material ${name} (${type})`);
  if (gradient !== undefined) {
    if (type !== "MeshToonMaterial") throw new Error(`material ${name}: a gradientMap needs MeshToonMaterial`);
    material.gradientMap = gradientMap(gradient);
  }
  return material;
}

function makeGeometry(description) {
  const { type, ...settings } = description;
  const names = GEOMETRY_ARGUMENTS[type];
  if (names === undefined) throw new Error(`unknown geometry type ${type}`);
  for (const key of Object.keys(settings)) {
    if (!names.includes(key)) throw new Error(`${type} takes no ${key}`);
  }
  const args = [];
  for (const key of names) {
    if (settings[key] === undefined) break;
    args.push(settings[key]);
  }
  return new THREE[type](...args);
}

function base64(bytes) {
  let text = "";
  const CHUNK = 0x8000;
  for (let i = 0; i < bytes.length; i += CHUNK) {
    text += String.fromCharCode.apply(null, bytes.subarray(i, i + CHUNK));
  }
  return btoa(text);
}

export function render(description) {
  const { width, height, camera: view, lights, materials, meshes } = description;

  const renderer = new THREE.WebGLRenderer({ antialias: false });
  const gl = renderer.getContext();
  if (!(gl instanceof WebGL2RenderingContext)) throw new Error("no WebGL2 context");
  if (!renderer.extensions.has("EXT_color_buffer_float")) {
    throw new Error("WebGL2 without EXT_color_buffer_float: no float render target");
  }
  renderer.toneMapping = THREE.NoToneMapping;
  renderer.shadowMap.enabled = false;
  renderer.setClearColor(0x000000, 0);

  const scene = new THREE.Scene();
  const camera = new THREE.PerspectiveCamera(view.fov, width / height, view.near, view.far);
  camera.position.copy(vector(view.position, "camera.position"));
  camera.lookAt(vector(view.lookAt, "camera.lookAt"));

  for (const light of lights) makeLight(scene, light);
  const byName = {};
  for (const [name, material] of Object.entries(materials)) byName[name] = makeMaterial(name, material);
  for (const description of meshes) {
    const material = byName[description.material];
    if (material === undefined) throw new Error(`no material named ${description.material}`);
    const mesh = new THREE.Mesh(makeGeometry(description.geometry), material);
    mesh.position.copy(vector(description.position, "mesh position"));
    if (description.rotation !== undefined) {
      const [x, y, z] = vector(description.rotation, "mesh rotation").toArray();
      mesh.rotation.set(x, y, z);
    }
    scene.add(mesh);
  }

  const target = new THREE.WebGLRenderTarget(width, height, {
    type: THREE.FloatType,
    format: THREE.RGBAFormat,
    depthBuffer: true,
    samples: 0,
  });
  renderer.setRenderTarget(target);
  renderer.render(scene, camera);
  const pixels = new Float32Array(width * height * 4);
  // A value no render writes: the read-back must overwrite it.
  pixels.fill(Number.NaN);
  renderer.readRenderTargetPixels(target, 0, 0, width, height, pixels);
  renderer.setRenderTarget(null);
  const error = gl.getError();
  if (error !== gl.NO_ERROR) throw new Error(`WebGL error 0x${error.toString(16)} after the render`);
  if (pixels.some(Number.isNaN)) throw new Error("the read-back left pixels unwritten (or NaN)");

  target.dispose();
  renderer.dispose();
  return {
    revision: THREE.REVISION,
    width,
    height,
    pixels: base64(new Uint8Array(pixels.buffer)),
  };
}
