//! Runs `kernel.wesl` (the material's lighting functions in a fragment shader, the stage
//! the material runs in) on the render device and reads the results back: the cases go in
//! as a data texture and come out as one pixel each of an `Rgba32Float` target. Both work on
//! every device, WebGL2 limits included.

use bevy::{
    prelude::*,
    render::{
        RenderApp,
        render_resource::{
            BindGroupEntries, BindGroupLayoutDescriptor, BindGroupLayoutEntries, BufferDescriptor,
            BufferUsages, CachedPipelineState, CachedRenderPipelineId, ColorTargetState,
            ColorWrites, CommandEncoderDescriptor, Extent3d, FragmentState, LoadOp, MapMode,
            Operations, Origin3d, PipelineCache, PollType, RenderPassColorAttachment,
            RenderPassDescriptor, RenderPipelineDescriptor, ShaderStages, StoreOp,
            TexelCopyBufferInfo, TexelCopyBufferLayout, TexelCopyTextureInfo, TextureAspect,
            TextureDescriptor, TextureDimension, TextureFormat, TextureSampleType, TextureUsages,
            TextureViewDescriptor, VertexState, binding_types::texture_2d,
        },
        renderer::{RenderDevice, RenderQueue},
    },
    shader::{Shader, ShaderCacheError},
};
use bevy_phong::testing::{DATA_TEXTURE_WIDTH, GpuLight};
use bevy_phong_headless::headless_app;
use bytemuck::{Pod, Zeroable};

/// One case as the kernel reads it (`ContractCase` in `kernel.wesl`): 10 texels.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct GpuCase {
    pub position: [f32; 3],
    pub kind: u32,
    pub normal: [f32; 3],
    pub shininess: f32,
    pub camera: [f32; 3],
    pub specular_model: u32,
    pub diffuse: [f32; 3],
    pub padding0: f32,
    pub specular: [f32; 3],
    pub padding1: f32,
    pub light: GpuLight,
}

/// One case of the area lights' kernel (`AreaCase` in `area_kernel.wesl`): 7 texels.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct AreaCase {
    pub position: [f32; 3],
    pub shininess: f32,
    pub normal: [f32; 3],
    pub specular_model: u32,
    pub camera: [f32; 3],
    pub padding: f32,
    /// The rectangle's corners, world space, in order around it (w unused).
    pub corners: [[f32; 4]; 4],
}

/// Pixels per row of the results target (`RESULTS_WIDTH` in `kernel.wesl`).
const RESULTS_WIDTH: u32 = 1024;
/// Cases per pass: 256 rows of results, and 10 · 2¹⁸ + 1 texels of cases (1,281 rows of
/// the data texture, within WebGL2's 2,048).
const BATCH: usize = 1 << 18;
const MAX_COMPILE_FRAMES: u32 = 600;

/// The compiled kernel and the app whose render device runs it.
pub struct ContractKernel {
    app: App,
    pipeline: CachedRenderPipelineId,
    layout: BindGroupLayoutDescriptor,
}

impl ContractKernel {
    /// Compiles the kernel's fragment `entry_point` through Bevy's pipeline cache, as
    /// material shaders are: `main` lights each case, `crate_highlight` and
    /// `naive_highlight` give the highlight factor of a directional light.
    pub fn new(entry_point: &'static str) -> Self {
        Self::compile(
            include_str!("kernel.wesl"),
            "tests/gpu/contract/kernel.wesl",
            entry_point,
        )
    }

    /// The area lights' kernel (`area_kernel.wesl`): each [`AreaCase`]'s integrals.
    pub fn area() -> Self {
        Self::compile(
            include_str!("area_kernel.wesl"),
            "tests/gpu/contract/area_kernel.wesl",
            "main",
        )
    }

    /// Compiles the kernel `source` (at `path`) with its fragment `entry_point`.
    fn compile(source: &'static str, path: &'static str, entry_point: &'static str) -> Self {
        let mut app = headless_app(|_| {});
        let shader = app
            .world_mut()
            .resource_mut::<Assets<Shader>>()
            .add(Shader::from_wesl(source, path));
        let layout = BindGroupLayoutDescriptor::new(
            "phong_contract",
            &BindGroupLayoutEntries::single(
                ShaderStages::FRAGMENT,
                texture_2d(TextureSampleType::Uint),
            ),
        );
        let pipeline = app
            .sub_app(RenderApp)
            .world()
            .resource::<PipelineCache>()
            .queue_render_pipeline(RenderPipelineDescriptor {
                label: Some("phong_contract".into()),
                layout: vec![layout.clone()],
                vertex: VertexState {
                    shader: shader.clone(),
                    entry_point: Some("cover".into()),
                    ..default()
                },
                fragment: Some(FragmentState {
                    shader,
                    entry_point: Some(entry_point.into()),
                    targets: vec![Some(ColorTargetState {
                        format: TextureFormat::Rgba32Float,
                        blend: None,
                        write_mask: ColorWrites::ALL,
                    })],
                    ..default()
                }),
                ..default()
            });
        for _ in 0..MAX_COMPILE_FRAMES {
            app.update();
            let cache = app.sub_app(RenderApp).world().resource::<PipelineCache>();
            match cache.get_render_pipeline_state(pipeline) {
                CachedPipelineState::Ok(_) => {
                    return Self {
                        app,
                        pipeline,
                        layout,
                    };
                }
                // Bevy retries these: a shader or one of its imports is still loading.
                CachedPipelineState::Err(
                    ShaderCacheError::ShaderNotLoaded(_)
                    | ShaderCacheError::ShaderImportNotYetAvailable,
                ) => {}
                CachedPipelineState::Err(error) => panic!("contract kernel: {error}"),
                _ => {}
            }
        }
        panic!("the contract kernel did not compile within {MAX_COMPILE_FRAMES} frames");
    }

    /// The result of every case: its lighting (linear RGB) for [`GpuCase`]s, the first
    /// three channels of its pixel for another kernel's cases.
    pub fn run<C: Pod>(&mut self, cases: &[C]) -> Vec<[f32; 3]> {
        cases
            .chunks(BATCH)
            .flat_map(|batch| self.run_batch(batch))
            .collect()
    }

    fn run_batch<C: Pod>(&mut self, cases: &[C]) -> Vec<[f32; 3]> {
        let world = self.app.sub_app(RenderApp).world();
        let device = world.resource::<RenderDevice>();
        let queue = world.resource::<RenderQueue>();
        let cache = world.resource::<PipelineCache>();
        let pipeline = cache
            .get_render_pipeline(self.pipeline)
            .expect("compiled in new()");

        // The count in texel 0, then the cases, in whole rows of the data texture.
        let mut texels: Vec<u8> = bytemuck::bytes_of(&[cases.len() as u32, 0, 0, 0]).to_vec();
        texels.extend_from_slice(bytemuck::cast_slice(cases));
        let input_rows = (texels.len() / 16).div_ceil(DATA_TEXTURE_WIDTH as usize) as u32;
        texels.resize((input_rows * DATA_TEXTURE_WIDTH * 16) as usize, 0);
        let input = device.create_texture_with_data(
            queue,
            &TextureDescriptor {
                label: Some("contract_cases"),
                size: Extent3d {
                    width: DATA_TEXTURE_WIDTH,
                    height: input_rows,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: TextureDimension::D2,
                format: TextureFormat::Rgba32Uint,
                usage: TextureUsages::TEXTURE_BINDING,
                view_formats: &[],
            },
            bevy::render::render_resource::TextureDataOrder::LayerMajor,
            &texels,
        );
        let rows = (cases.len() as u32).div_ceil(RESULTS_WIDTH);
        let size = Extent3d {
            width: RESULTS_WIDTH,
            height: rows,
            depth_or_array_layers: 1,
        };
        let results = device.create_texture(&TextureDescriptor {
            label: Some("contract_results"),
            size,
            mip_level_count: 1,
            sample_count: 1,
            dimension: TextureDimension::D2,
            format: TextureFormat::Rgba32Float,
            usage: TextureUsages::RENDER_ATTACHMENT | TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        // 16 bytes a pixel: a row of 1,024 is 16 KiB, a multiple of wgpu's 256-byte alignment.
        let bytes_per_row = RESULTS_WIDTH * 16;
        let staging_size = u64::from(bytes_per_row * rows);
        let staging = device.create_buffer(&BufferDescriptor {
            label: Some("contract_staging"),
            size: staging_size,
            usage: BufferUsages::MAP_READ | BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let layout = cache.get_bind_group_layout(&self.layout);
        let input_view = input.create_view(&TextureViewDescriptor::default());
        let bind_group =
            device.create_bind_group("contract", &layout, &BindGroupEntries::single(&input_view));
        let results_view = results.create_view(&TextureViewDescriptor::default());
        let mut encoder = device.create_command_encoder(&CommandEncoderDescriptor::default());
        {
            let mut pass = encoder.begin_render_pass(&RenderPassDescriptor {
                label: Some("contract"),
                color_attachments: &[Some(RenderPassColorAttachment {
                    view: &results_view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: Operations {
                        load: LoadOp::Clear(Default::default()),
                        store: StoreOp::Store,
                    },
                })],
                ..default()
            });
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, &bind_group, &[]);
            pass.draw(0..3, 0..1);
        }
        encoder.copy_texture_to_buffer(
            TexelCopyTextureInfo {
                texture: &results,
                mip_level: 0,
                origin: Origin3d::ZERO,
                aspect: TextureAspect::All,
            },
            TexelCopyBufferInfo {
                buffer: &staging,
                layout: TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(bytes_per_row),
                    rows_per_image: Some(rows),
                },
            },
            size,
        );
        queue.submit([encoder.finish()]);

        let slice = staging.slice(..);
        slice.map_async(MapMode::Read, |result| {
            result.expect("map contract results")
        });
        device
            .poll(PollType::wait_indefinitely())
            .expect("the device finishes the kernel");
        let mapped = slice
            .get_mapped_range()
            .expect("the results buffer is mapped");
        let results = bytemuck::cast_slice::<u8, [f32; 4]>(&mapped)
            .iter()
            .take(cases.len())
            .map(|rgba| [rgba[0], rgba[1], rgba[2]])
            .collect();
        drop(mapped);
        staging.unmap();
        results
    }
}
