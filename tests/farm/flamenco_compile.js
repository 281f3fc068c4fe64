// Compiles a Flamenco job type the way a Flamenco Manager does, with stand-ins for the Manager's job
// compiler API (author.Task, author.Command, frameChunker, path, print), and prints the job's tasks as
// JSON: [{name, type, commands: [{name, parameters}], dependencies: [task names]}].
//   node tests/farm/flamenco_compile.js JOB_TYPE.js '{"frames": "1-48", ...settings}'
// The stand-ins follow Flamenco's documented behaviour; this is no Flamenco Manager.
"use strict";
const fs = require("fs");
const vm = require("vm");

// As the Manager's frameChunker: the frames of "1-10,12" or "1..10,12" (Blender's notation), without
// repeats and sorted, cut into chunks of `size` frames each, whatever the gaps; a chunk is written as its
// runs of consecutive frames joined by commas, a run as "A-B", a run of two as "A,B", one frame as "A".
function frameChunker(frames, size) {
    const unique = new Set();
    for (const part of String(frames).replaceAll("..", "-").split(",")) {
        const ends = part.split("-").map((text) => text.trim());
        if (ends.length > 2 || ends.some((text) => !/^\d+$/.test(text))) throw `invalid range "${frames}"`;
        for (let frame = Number(ends[0]); frame <= Number(ends[ends.length - 1]); frame++) unique.add(frame);
    }
    const list = [...unique].sort((a, b) => a - b);
    const chunks = [];
    for (let start = 0; start < list.length; start += size) {
        const runs = [];
        let first = start;
        const end = Math.min(start + size, list.length);
        for (let i = start + 1; i <= end; i++) {
            if (i < end && list[i] === list[i - 1] + 1) continue;
            const [a, b] = [list[first], list[i - 1]];
            runs.push(a === b ? `${a}` : b === a + 1 ? `${a},${b}` : `${a}-${b}`);
            first = i;
        }
        chunks.push(runs.join(","));
    }
    return chunks;
}

const tasks = [];
const author = {
    Task(name, type) {
        const task = { name, type, commands: [], dependencies: [] };
        return {
            record: task,
            addCommand(command) { task.commands.push(command); },
            addDependency(other) { task.dependencies.push(other.record.name); },
        };
    },
    Command(name, parameters) { return { name, parameters }; },
};
const job = {
    settings: JSON.parse(process.argv[3]),
    created: new Date(),
    addTask(task) { tasks.push(task.record); },
};
const sandbox = { author, frameChunker, path: require("path").posix, print: (...a) => console.error(...a), job };
vm.createContext(sandbox);
vm.runInContext(fs.readFileSync(process.argv[2], "utf8") + "\ncompileJob(job);", sandbox, { filename: process.argv[2] });
console.log(JSON.stringify(tasks));
