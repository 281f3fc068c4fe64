// Compiles a Flamenco job type the way a Flamenco Manager does, with stand-ins for the Manager's job
// compiler API (author.Task, author.Command, frameChunker, path, print), and prints the job's tasks as
// JSON: [{name, type, commands: [{name, parameters}], dependencies: [task names]}].
//   node tests/farm/flamenco_compile.js JOB_TYPE.js '{"frames": "1-48", ...settings}'
// The stand-ins follow Flamenco's documented behaviour; this is no Flamenco Manager.
"use strict";
const fs = require("fs");
const vm = require("vm");

// "1-10,12" -> chunks of at most `size` consecutive frames, each "A-B" (or "A" for one frame).
function frameChunker(frames, size) {
    const list = [];
    for (const part of String(frames).split(",")) {
        const match = /^\s*(-?\d+)\s*(?:-\s*(-?\d+)\s*)?$/.exec(part);
        if (!match) throw `bad frame range ${frames}`;
        const first = Number(match[1]);
        const last = match[2] === undefined ? first : Number(match[2]);
        for (let frame = first; frame <= last; frame++) list.push(frame);
    }
    const chunks = [];
    let start = 0;
    while (start < list.length) {
        let end = start;
        while (end + 1 < list.length && end + 1 - start < size && list[end + 1] === list[end] + 1) end++;
        chunks.push(start === end ? `${list[start]}` : `${list[start]}-${list[end]}`);
        start = end + 1;
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
