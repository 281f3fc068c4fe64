// Flamenco job type: a Gauss Stylization animation bake in chunks, then the merge (docs/baking.md,
// "Flamenco"). Put this file in the Manager's scripts/ folder next to flamenco-manager; the Blender
// add-on of Flamenco then offers "Gauss Stylization Bake" as a job type. Every worker needs Blender with
// the Gauss Stylization add-on installed; farm_cli is where its bake/farm_cli.py is on the workers.

const JOB_TYPE = {
    label: "Gauss Stylization Bake",
    description: "Bake a Gauss-stylized animation to a .pc2 point cache, in chunks of frames, then merge them",
    settings: [
        // Filled in by the Flamenco add-on when the job is submitted from Blender.
        { key: "frames", type: "string", required: true,
          eval: "f'{C.scene.frame_start}-{C.scene.frame_end}'",
          description: "Frames to bake, A-B" },
        { key: "object", type: "string", required: true, eval: "C.active_object.name",
          description: "The mesh object to bake (its Gauss settings in the .blend are used)" },
        { key: "chunk_size", type: "int32", default: 60, propargs: { min: 1 },
          description: "Frames per task: each task starts Blender and sets up the solver once" },
        { key: "output", type: "string", subtype: "file_path", required: true,
          description: "The merged .pc2 file; the chunks go to <output>.chunks/" },
        { key: "farm_cli", type: "string", subtype: "file_path", required: true,
          description: "The add-on's bake/farm_cli.py as installed on the workers" },
        // Set by the Flamenco add-on itself.
        { key: "blendfile", type: "string", required: true, visible: "web",
          description: "Path of the Blend file to bake" },
    ],
};

function compileJob(job) {
    const settings = job.settings;
    checkOneRange(settings.frames);
    const chunkDir = settings.output + ".chunks";
    const bakeTasks = [];
    for (const chunk of frameChunker(settings.frames, settings.chunk_size)) {
        const task = author.Task(`bake-${chunk}`, "blender");
        task.addCommand(author.Command("blender-render", {
            exe: "{blender}",
            exeArgs: "{blenderArgs}",
            argsBefore: [],
            blendfile: settings.blendfile,
            args: farmCli(settings, ["bake", "--object", settings.object, "--frames", chunk,
                                     "--out", path.join(chunkDir, `chunk_${chunk}.pc2`)]),
        }));
        job.addTask(task);
        bakeTasks.push(task);
    }
    // The merge opens the same .blend (the blender-render command wants one) but only reads the chunks.
    const merge = author.Task("merge", "blender");
    merge.addCommand(author.Command("blender-render", {
        exe: "{blender}",
        exeArgs: "{blenderArgs}",
        argsBefore: [],
        blendfile: settings.blendfile,
        args: farmCli(settings, ["merge", path.join(chunkDir, "chunk_*.pc2"), "--frames", settings.frames,
                                 "--out", settings.output]),
    }));
    for (const task of bakeTasks) {
        merge.addDependency(task);
    }
    job.addTask(merge);
}

// A bake's chunks must join into one cache without gaps, so refuse a frame list such as "1-10,20-30" when
// the job is submitted, rather than let its tasks fail on the workers.
function checkOneRange(frames) {
    if (!/^\s*\d+\s*((-|\.\.)\s*\d+\s*)?$/.test(String(frames))) {
        throw `Frames must be one range A-B (e.g. 1-240), got "${frames}"`;
    }
}

// The farm command line after the .blend: an error in the script makes Blender exit non-zero, so the
// task fails instead of passing with no file.
function farmCli(settings, jobArgs) {
    return ["--python-exit-code", "1", "-P", settings.farm_cli, "--"].concat(jobArgs);
}
