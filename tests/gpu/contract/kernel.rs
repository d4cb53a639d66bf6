//! Runs `kernel.wgsl` (the material's lighting functions in a compute shader) on the render
//! device and reads the results back.

use bevy::{
    prelude::*,
    render::{
        RenderApp,
        render_resource::{
            BindGroupEntries, BindGroupLayoutDescriptor, BindGroupLayoutEntries, BufferDescriptor,
            BufferUsages, CachedComputePipelineId, CachedPipelineState, CommandEncoderDescriptor,
            ComputePassDescriptor, ComputePipelineDescriptor, MapMode, PipelineCache, PollType,
            ShaderStages,
            binding_types::{storage_buffer_read_only_sized, storage_buffer_sized},
        },
        renderer::{RenderDevice, RenderQueue},
    },
    shader::{Shader, ShaderCacheError},
};
use bevy_phong::render::GpuLight;
use bevy_phong_headless::headless_app;
use bytemuck::{Pod, Zeroable};

/// One case as the kernel reads it (`ContractCase` in `kernel.wgsl`).
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

/// Cases per dispatch: well under the device's storage binding limit.
const BATCH: usize = 1 << 18;
const WORKGROUP_SIZE: usize = 64;
const MAX_COMPILE_FRAMES: u32 = 600;

/// The compiled kernel and the app whose render device runs it.
pub struct ContractKernel {
    app: App,
    pipeline: CachedComputePipelineId,
    layout: BindGroupLayoutDescriptor,
}

impl ContractKernel {
    /// Compiles the kernel's `entry_point` through Bevy's pipeline cache, as material shaders
    /// are: `main` lights each case, `crate_highlight` and `naive_highlight` give the highlight
    /// factor of a directional light.
    pub fn new(entry_point: &'static str) -> Self {
        let mut app = headless_app(|_| {});
        let shader = app
            .world_mut()
            .resource_mut::<Assets<Shader>>()
            .add(Shader::from_wgsl(
                include_str!("kernel.wgsl"),
                "tests/gpu/contract/kernel.wgsl",
            ));
        let layout = BindGroupLayoutDescriptor::new(
            "phong_contract",
            &BindGroupLayoutEntries::sequential(
                ShaderStages::COMPUTE,
                (
                    storage_buffer_read_only_sized(false, None),
                    storage_buffer_sized(false, None),
                ),
            ),
        );
        let pipeline = app
            .sub_app(RenderApp)
            .world()
            .resource::<PipelineCache>()
            .queue_compute_pipeline(ComputePipelineDescriptor {
                label: Some("phong_contract".into()),
                layout: vec![layout.clone()],
                shader,
                entry_point: Some(entry_point.into()),
                zero_initialize_workgroup_memory: true,
                ..default()
            });
        for _ in 0..MAX_COMPILE_FRAMES {
            app.update();
            let cache = app.sub_app(RenderApp).world().resource::<PipelineCache>();
            match cache.get_compute_pipeline_state(pipeline) {
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

    /// The lighting result (linear RGB) of every case.
    pub fn run(&mut self, cases: &[GpuCase]) -> Vec<[f32; 3]> {
        cases
            .chunks(BATCH)
            .flat_map(|batch| self.run_batch(batch))
            .collect()
    }

    fn run_batch(&mut self, cases: &[GpuCase]) -> Vec<[f32; 3]> {
        let world = self.app.sub_app(RenderApp).world();
        let device = world.resource::<RenderDevice>();
        let queue = world.resource::<RenderQueue>();
        let cache = world.resource::<PipelineCache>();
        let pipeline = cache
            .get_compute_pipeline(self.pipeline)
            .expect("compiled in new()");
        let input =
            device.create_buffer_with_data(&bevy::render::render_resource::BufferInitDescriptor {
                label: Some("contract_cases"),
                contents: bytemuck::cast_slice(cases),
                usage: BufferUsages::STORAGE,
            });
        let output_size = (cases.len() * 16) as u64;
        let output = device.create_buffer(&BufferDescriptor {
            label: Some("contract_results"),
            size: output_size,
            usage: BufferUsages::STORAGE | BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let staging = device.create_buffer(&BufferDescriptor {
            label: Some("contract_staging"),
            size: output_size,
            usage: BufferUsages::MAP_READ | BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let layout = cache.get_bind_group_layout(&self.layout);
        let bind_group = device.create_bind_group(
            "contract",
            &layout,
            &BindGroupEntries::sequential((input.as_entire_binding(), output.as_entire_binding())),
        );
        let mut encoder = device.create_command_encoder(&CommandEncoderDescriptor::default());
        {
            let mut pass = encoder.begin_compute_pass(&ComputePassDescriptor::default());
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, &bind_group, &[]);
            pass.dispatch_workgroups(cases.len().div_ceil(WORKGROUP_SIZE) as u32, 1, 1);
        }
        encoder.copy_buffer_to_buffer(&output, 0, &staging, 0, output_size);
        queue.submit([encoder.finish()]);

        let slice = staging.slice(..);
        slice.map_async(MapMode::Read, |result| {
            result.expect("map contract results")
        });
        device
            .poll(PollType::wait_indefinitely())
            .expect("the device finishes the kernel");
        let results = bytemuck::cast_slice::<u8, [f32; 4]>(&slice.get_mapped_range())
            .iter()
            .map(|rgba| [rgba[0], rgba[1], rgba[2]])
            .collect();
        staging.unmap();
        results
    }
}
