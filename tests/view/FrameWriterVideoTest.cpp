// A video written through FrameWriter and the FFmpeg module, decoded back with FFmpeg's own
// libraries: an H.264 stream of the given size, rate and frame count, frames in order. Built
// (as mvcl_video_tests, apart from mvcl_tests, which should not load FFmpeg) only with the module.

#include <mvcl/view/FrameWriter.h>

#include <gtest/gtest.h>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
}

#include <filesystem>
#include <vector>

namespace fs = std::filesystem;
using namespace mvcl;

namespace {

struct DecodedVideo {
    AVCodecID codec = AV_CODEC_ID_NONE;
    int width = 0, height = 0;
    AVRational frameRate{0, 1};
    std::vector<int> centreLuma; ///< Y of the centre pixel of each decoded frame, in order
};

DecodedVideo decode(const std::string &path) {
    DecodedVideo video;
    AVFormatContext *format = nullptr;
    if (avformat_open_input(&format, path.c_str(), nullptr, nullptr) < 0) return video;
    avformat_find_stream_info(format, nullptr);
    const int index = av_find_best_stream(format, AVMEDIA_TYPE_VIDEO, -1, -1, nullptr, 0);
    if (index >= 0) {
        const AVCodecParameters *parameters = format->streams[index]->codecpar;
        video.codec = parameters->codec_id;
        video.width = parameters->width;
        video.height = parameters->height;
        video.frameRate = format->streams[index]->avg_frame_rate;
        const AVCodec *decoder = avcodec_find_decoder(parameters->codec_id);
        AVCodecContext *context = avcodec_alloc_context3(decoder);
        avcodec_parameters_to_context(context, parameters);
        avcodec_open2(context, decoder, nullptr);
        AVPacket *packet = av_packet_alloc();
        AVFrame *frame = av_frame_alloc();
        const auto drain = [&] {
            while (avcodec_receive_frame(context, frame) == 0)
                video.centreLuma.push_back(
                    frame->data[0][(frame->height / 2) * frame->linesize[0] + frame->width / 2]);
        };
        while (av_read_frame(format, packet) >= 0) {
            if (packet->stream_index == index && avcodec_send_packet(context, packet) == 0) drain();
            av_packet_unref(packet);
        }
        avcodec_send_packet(context, nullptr);
        drain();
        av_frame_free(&frame);
        av_packet_free(&packet);
        avcodec_free_context(&context);
    }
    avformat_close_input(&format);
    return video;
}

} // namespace

TEST(FrameWriterVideo, AnMp4HoldsEveryFrameAsH264AtTheFrameRate) {
    const fs::path dir = fs::temp_directory_path() / "mvcl-frame-writer-video-test";
    fs::remove_all(dir);
    const std::string file = (dir / "clip.mp4").string();
    {
        FrameWriter writer(file, 64, 48, 25.0);
        EXPECT_TRUE(writer.writesVideo());
        for (int frame = 0; frame < 5; ++frame) {
            Framebuffer image(64, 48);
            for (glm::vec3 &pixel : image.pixels()) pixel = glm::vec3(0.05f + 0.2f * float(frame));
            writer.write(frame, image);
        }
        writer.finish();
    }
    const DecodedVideo video = decode(file);
    EXPECT_EQ(video.codec, AV_CODEC_ID_H264);
    EXPECT_EQ(video.width, 64);
    EXPECT_EQ(video.height, 48);
    EXPECT_EQ(av_cmp_q(video.frameRate, AVRational{25, 1}), 0);
    ASSERT_EQ(video.centreLuma.size(), 5u);
    for (std::size_t i = 1; i < video.centreLuma.size(); ++i)
        EXPECT_GT(video.centreLuma[i], video.centreLuma[i - 1] + 10) << "frame " << i << " is out of order";
}

TEST(FrameWriterVideo, AnOddSizedImageBecomesAnEvenSizedVideo) {
    const fs::path dir = fs::temp_directory_path() / "mvcl-frame-writer-video-test";
    const std::string file = (dir / "odd.mkv").string();
    {
        FrameWriter writer(file, 33, 21, 30.0);
        writer.write(0, Framebuffer(33, 21));
        writer.finish();
    }
    const DecodedVideo video = decode(file);
    EXPECT_EQ(video.width, 32); // 4:2:0 chroma needs even sides
    EXPECT_EQ(video.height, 20);
    EXPECT_EQ(video.centreLuma.size(), 1u);
}
