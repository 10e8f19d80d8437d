//! A `ReadBack` made once reads a buffer back as often as asked, the first `bytes` of it, and
//! refuses more than it holds with a typed error.

use gpu_harness::{GpuError, ReadBack, gpu_test_context};

#[test]
fn a_kept_staging_buffer_reads_back_every_time_and_refuses_too_much() {
    let Some(ctx) = gpu_test_context() else { return };
    let (device, queue) = (&ctx.device, &ctx.queue);
    let values: Vec<u32> = (0..64).collect();
    let src = gpu_harness::storage_buffer(device, "values", bytemuck::cast_slice(&values));
    let read_back = ReadBack::new(device, "kept", 64 * 4);
    for (k, bytes) in [(1u32, 256u64), (2, 40), (3, 256)] {
        queue.write_buffer(
            &src,
            0,
            bytemuck::cast_slice(&values.iter().map(|v| v * k).collect::<Vec<_>>()),
        );
        let enc = device.create_command_encoder(&Default::default());
        let got: Vec<u32> = bytemuck::pod_collect_to_vec(
            &read_back.read_after(device, queue, enc, &src, bytes).unwrap(),
        );
        let want: Vec<u32> = values.iter().take(bytes as usize / 4).map(|v| v * k).collect();
        assert_eq!(got, want, "read {k}: the first {bytes} bytes as written");
    }
    let enc = device.create_command_encoder(&Default::default());
    assert!(matches!(
        read_back.read_after(device, queue, enc, &src, 260),
        Err(GpuError::ReadBackTooLarge { bytes: 260, capacity: 256 })
    ));
}
